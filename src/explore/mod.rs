//! `archstudy explore`: one arch, live, in the browser. A small read-only HTTP server on the
//! local machine serves a page (built into the binary) and answers its questions about a
//! scene with the library's own analysis, drawn by the report's own chart code as SVG: the
//! page draws no picture of its own, it places the server's figures and turns a click on a
//! map into the map's (μ, K) through the plotting frame the server sends with it.
//!
//! Routes (all `GET`; `HEAD` too):
//! - `/`, `/app.js`, `/app.css`: the page.
//! - `/api/scene?SCENE`: the state, the critical finds, what is drawn and the state and
//!   Fig. 2 figures of a scene (SCENE: the keywords of `archstudy.solve`, see
//!   [`query::SCENE_PARAMETERS`]).
//! - `/api/mechanism?SCENE`: the frames of the collapse mechanism of the scene's limit state.
//! - `/api/map?SCENE&MAP`: the regime map of a K × μ window around the scene, its boundaries
//!   and bifurcations located as a run locates them (capped in points).
//! - `/api/figure?view=state|domains|mechanism|map|run&format=svg|pdf&SCENE&MAP`: a view as
//!   the report's paper figure, to download.
//! - `/api/study?SCENE&MAP`: the manifest of the map's study, to download.
//! - `/api/run`, `/api/run/case?panel=&x=&y=` or `?case=ID`: the run directory given on the
//!   command line, its figure and any of its cases.
//! - `/run/PATH`: a file of the run directory (never one outside it).
//!
//! A bad query is answered with status 400 and a JSON body naming the parameter, the value
//! and what is allowed. Work is bounded per request (voussoir counts, map points) and in
//! all ([`MAX_CONCURRENT_WORK`] analyses at once, the rest wait).

mod assets;
pub mod map;
pub mod query;
mod routes;
pub mod run_view;
pub mod study;
pub mod views;

use anyhow::{Context, Result};
use http_body_util::Full;
use hyper::body::{Bytes, Incoming};
use hyper::server::conn::http1;
use hyper::service::service_fn;
use hyper::{Method, Request, Response, StatusCode};
use hyper_util::rt::{TokioIo, TokioTimer};
use std::convert::Infallible;
use std::net::SocketAddr;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Duration;
use tokio::sync::Semaphore;

/// Analyses that run at once; further requests wait for one to finish.
pub const MAX_CONCURRENT_WORK: usize = 8;
/// How long a request waits for its analysis before it is answered 503 (the analysis itself
/// cannot be stopped midway and runs to its end).
pub const WORK_BUDGET: Duration = Duration::from_secs(20);
/// Connections served at once; further connections wait to be accepted.
pub const MAX_CONNECTIONS: usize = 512;
/// The longest request target (path and query), bytes.
pub const MAX_TARGET_BYTES: usize = 8192;
/// How long a client may take to send its request head.
pub const HEADER_TIMEOUT: Duration = Duration::from_secs(10);

/// What `archstudy explore` serves, and where.
#[derive(Debug, Clone)]
pub struct ExploreOptions {
    /// A run directory to open the page on (its figure and cases).
    pub run_dir: Option<PathBuf>,
    /// The address to listen on (127.0.0.1 unless told otherwise).
    pub host: String,
    /// The port (0: any free port).
    pub port: u16,
}

/// The state shared by every request.
pub(crate) struct App {
    /// The run directory opened, if any.
    pub run: Option<run_view::RunView>,
    /// Permits for analyses.
    pub work: Arc<Semaphore>,
    /// The Host header values taken when listening on loopback (`None`: any, for a server
    /// that was asked to listen on another address).
    pub hosts: Option<Vec<String>>,
}

impl App {
    /// True when a request's Host header names this server: on loopback, `localhost`,
    /// `127.0.0.1` or `[::1]` with the port listened on, so that a page elsewhere whose name
    /// is rebound to this machine cannot read it.
    fn host_allowed(&self, host: Option<&hyper::header::HeaderValue>) -> bool {
        match (&self.hosts, host.and_then(|h| h.to_str().ok())) {
            (None, _) => true,
            (Some(hosts), Some(h)) => hosts.iter().any(|a| a.eq_ignore_ascii_case(h)),
            (Some(_), None) => false,
        }
    }
}

/// The address could not be listened on: a host that names no address of this machine, a
/// port in use or not allowed.
#[derive(Debug, thiserror::Error)]
#[error("cannot listen on {host}:{port}: {reason}")]
pub struct ListenError {
    /// The host given.
    pub host: String,
    /// The port given.
    pub port: u16,
    /// What went wrong, as the system says.
    pub kind: std::io::ErrorKind,
    /// The system's message.
    pub reason: String,
}

impl ListenError {
    /// True when the port is at fault (in use, or one this user may not take), false when
    /// the host is.
    pub fn port_at_fault(&self) -> bool {
        matches!(
            self.kind,
            std::io::ErrorKind::AddrInUse | std::io::ErrorKind::PermissionDenied
        )
    }
}

/// A running explorer.
pub struct Explorer {
    addr: SocketAddr,
    runtime: tokio::runtime::Runtime,
    accept: tokio::task::JoinHandle<()>,
}

impl Explorer {
    /// The address it listens on.
    pub fn addr(&self) -> SocketAddr {
        self.addr
    }

    /// The page's address.
    pub fn url(&self) -> String {
        format!("http://{}/", self.addr)
    }

    /// Serves until the process ends.
    pub fn wait(self) -> Result<()> {
        self.runtime
            .block_on(self.accept)
            .context("the explorer's server stopped")
    }

    /// Stops serving: no new connection is accepted, open ones are dropped.
    pub fn stop(self) {
        self.accept.abort();
        self.runtime.shutdown_background();
    }
}

/// Opens the run directory (if any), binds the address and starts serving in the background.
pub fn start(opts: &ExploreOptions) -> Result<Explorer> {
    let run = match &opts.run_dir {
        Some(d) => Some(run_view::RunView::open(d)?),
        None => None,
    };

    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .thread_name("explore")
        .enable_io()
        .enable_time()
        .build()
        .context("cannot start the explorer's server")?;
    let host = opts.host.trim_start_matches('[').trim_end_matches(']');
    let listener = runtime
        .block_on(tokio::net::TcpListener::bind((host, opts.port)))
        .map_err(|e| ListenError {
            host: opts.host.clone(),
            port: opts.port,
            kind: e.kind(),
            reason: e.to_string(),
        })?;
    let addr = listener.local_addr()?;
    let port = addr.port();
    let hosts = addr.ip().is_loopback().then(|| {
        ["localhost", "127.0.0.1", "[::1]"]
            .iter()
            .map(|h| format!("{h}:{port}"))
            .collect()
    });
    let app = Arc::new(App {
        run,
        work: Arc::new(Semaphore::new(MAX_CONCURRENT_WORK)),
        hosts,
    });
    let accept = runtime.spawn(accept_loop(listener, app));
    Ok(Explorer {
        addr,
        runtime,
        accept,
    })
}

async fn accept_loop(listener: tokio::net::TcpListener, app: Arc<App>) {
    let connections = Arc::new(Semaphore::new(MAX_CONNECTIONS));
    loop {
        let Ok(permit) = connections.clone().acquire_owned().await else {
            return;
        };
        let Ok((stream, _)) = listener.accept().await else {
            // Out of file descriptors or a reset before accept: try again shortly.
            tokio::time::sleep(Duration::from_millis(10)).await;
            continue;
        };
        let app = app.clone();
        tokio::spawn(async move {
            let service = service_fn(move |req| answer(req, app.clone()));
            let _ = http1::Builder::new()
                .timer(TokioTimer::new())
                .header_read_timeout(HEADER_TIMEOUT)
                .max_buf_size(16 * 1024)
                .serve_connection(TokioIo::new(stream), service)
                .await;
            drop(permit);
        });
    }
}

/// One answer: status, content type, body and, for a download, its file name.
#[derive(Debug, Clone)]
pub(crate) struct Reply {
    pub status: StatusCode,
    pub content_type: &'static str,
    pub body: Vec<u8>,
    pub download: Option<String>,
}

impl Reply {
    pub fn ok(content_type: &'static str, body: impl Into<Vec<u8>>) -> Self {
        Reply {
            status: StatusCode::OK,
            content_type,
            body: body.into(),
            download: None,
        }
    }

    pub fn json(v: &serde_json::Value) -> Self {
        Reply::ok(
            "application/json",
            serde_json::to_vec(v).unwrap_or_default(),
        )
    }

    pub fn error(status: StatusCode, message: &str) -> Self {
        let mut r = Reply::json(&serde_json::json!({ "error": message }));
        r.status = status;
        r
    }
}

async fn answer(
    req: Request<Incoming>,
    app: Arc<App>,
) -> Result<Response<Full<Bytes>>, Infallible> {
    let head = req.method() == Method::HEAD;
    let reply = if !app.host_allowed(req.headers().get(hyper::header::HOST)) {
        Reply::error(
            StatusCode::MISDIRECTED_REQUEST,
            "this server answers requests for its own address only (the Host header names \
             another: a page that rebinds its name to this machine)",
        )
    } else if req.method() != Method::GET && !head {
        Reply::error(
            StatusCode::METHOD_NOT_ALLOWED,
            "the explorer is read-only: GET and HEAD only",
        )
    } else {
        let target = req.uri().path_and_query().map_or("/", |p| p.as_str());
        if target.len() > MAX_TARGET_BYTES {
            Reply::error(
                StatusCode::URI_TOO_LONG,
                &format!("a request target of at most {MAX_TARGET_BYTES} bytes"),
            )
        } else {
            let path = req.uri().path().to_string();
            let query = req.uri().query().unwrap_or("").to_string();
            routed(path, query, app).await
        }
    };
    Ok(response(reply, head))
}

async fn routed(path: String, query: String, app: Arc<App>) -> Reply {
    if let Some(r) = assets::asset(&path) {
        return r;
    }
    if !path.starts_with("/api/") && !path.starts_with("/run/") {
        return Reply::error(StatusCode::NOT_FOUND, &format!("no page at {path}"));
    }
    // Files and the run's description need no analysis: they never wait behind one.
    let analysis = !(path.starts_with("/run/") || path == "/api/run" || path == "/api/study");
    let permit = if analysis {
        match app.work.clone().acquire_owned().await {
            Ok(p) => Some(p),
            Err(_) => {
                return Reply::error(StatusCode::SERVICE_UNAVAILABLE, "the server is stopping");
            }
        }
    } else {
        None
    };
    let worker = app.clone();
    let task = tokio::task::spawn_blocking(move || {
        let reply = routes::route(&path, &query, &worker);
        // The permit is held until the analysis ends, answered in time or not: at most
        // MAX_CONCURRENT_WORK analyses ever run at once.
        drop(permit);
        reply
    });
    match tokio::time::timeout(WORK_BUDGET, task).await {
        Ok(Ok(r)) => r,
        Ok(Err(_)) => Reply::error(
            StatusCode::INTERNAL_SERVER_ERROR,
            "the analysis of this request failed (a panic)",
        ),
        Err(_) => Reply::error(
            StatusCode::SERVICE_UNAVAILABLE,
            &format!(
                "this scene takes longer than {} s to analyse here (the analysis goes on \
                 until it ends, holding one of {MAX_CONCURRENT_WORK} workers); ask \
                 `archstudy solve` for it",
                WORK_BUDGET.as_secs()
            ),
        ),
    }
}

fn response(r: Reply, head: bool) -> Response<Full<Bytes>> {
    let mut b = Response::builder()
        .status(r.status)
        .header("content-type", r.content_type)
        .header("cache-control", "no-store")
        .header("x-content-type-options", "nosniff")
        .header(
            "content-security-policy",
            "default-src 'none'; script-src 'self'; style-src 'self' 'unsafe-inline'; \
             img-src 'self' data:; connect-src 'self'; font-src 'self' data:",
        );
    if let Some(name) = &r.download {
        b = b.header(
            "content-disposition",
            format!("attachment; filename=\"{name}\""),
        );
    }
    let body = if head { Vec::new() } else { r.body };
    b.body(Full::new(Bytes::from(body)))
        .unwrap_or_else(|_| Response::new(Full::new(Bytes::new())))
}
