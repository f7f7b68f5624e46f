//! The page's files, built into the binary: no build step and no network are needed to
//! serve it.

use super::Reply;

const INDEX: &str = include_str!("assets/index.html");
const SCRIPT: &str = include_str!("assets/app.js");
const STYLE: &str = include_str!("assets/app.css");

/// The asset at `path`, if there is one.
pub(super) fn asset(path: &str) -> Option<Reply> {
    Some(match path {
        "/" | "/index.html" => Reply::ok("text/html; charset=utf-8", INDEX),
        "/app.js" => Reply::ok("text/javascript; charset=utf-8", SCRIPT),
        "/app.css" => Reply::ok("text/css; charset=utf-8", STYLE),
        _ => return None,
    })
}
