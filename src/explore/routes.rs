//! The answers of the API routes and of the run directory's files (blocking work, run on
//! the blocking pool).

use super::query::{MAP_PARAMETERS, Query, QueryError, SCENE_PARAMETERS};
use super::study::{MapWindow, manifest_text};
use super::views::{self, Answers, SceneView};
use super::{App, Reply};
use crate::report::charts::FigureSpec;
use crate::scene::Solution;
use hyper::StatusCode;
use serde_json::json;
use std::path::Path;

/// The parameters of a figure download besides the scene and the map.
const FIGURE_PARAMETERS: [&str; 2] = ["view", "format"];
/// The parameters of a case of the run.
const CASE_PARAMETERS: [&str; 4] = ["panel", "x", "y", "case"];
/// The largest file of a run directory served, bytes.
const MAX_FILE_BYTES: u64 = 256 << 20;

pub(super) fn route(path: &str, query: &str, app: &App) -> Reply {
    let answer = match path {
        "/api/scene" => scene(query),
        "/api/mechanism" => mechanism(query),
        "/api/map" => map(query),
        "/api/figure" => figure(query, app),
        "/api/study" => study(query),
        "/api/run" => run(query, app),
        "/api/run/case" => case(query, app),
        p if p.starts_with("/run/") => return run_file(&p["/run/".len()..], app),
        _ => return Reply::error(StatusCode::NOT_FOUND, &format!("no route {path}")),
    };
    answer.unwrap_or_else(|e| match e {
        Failure::Query(q) => {
            let mut r = Reply::json(&json!({
                "error": q.to_string(),
                "parameter": q.parameter,
                "value": q.value,
                "allowed": q.allowed,
            }));
            r.status = StatusCode::BAD_REQUEST;
            r
        }
        Failure::NotFound(m) => Reply::error(StatusCode::NOT_FOUND, &m),
        Failure::Internal(e) => Reply::error(StatusCode::INTERNAL_SERVER_ERROR, &format!("{e:#}")),
    })
}

/// Why a route gives no answer.
enum Failure {
    /// A bad query: 400.
    Query(QueryError),
    /// Nothing there: 404.
    NotFound(String),
    /// The analysis or the drawing failed: 500.
    Internal(anyhow::Error),
}

impl From<QueryError> for Failure {
    fn from(e: QueryError) -> Self {
        Failure::Query(e)
    }
}

impl From<anyhow::Error> for Failure {
    fn from(e: anyhow::Error) -> Self {
        match e.downcast::<QueryError>() {
            Ok(q) => Failure::Query(q),
            Err(e) => Failure::Internal(e),
        }
    }
}

type Answer = Result<Reply, Failure>;

fn parse(query: &str, groups: &[&[&str]]) -> Result<Query, Failure> {
    Ok(Query::parse(query, groups)?)
}

fn view_of(q: &Query, answers: Answers) -> Result<SceneView, Failure> {
    Ok(views::scene_view(&q.scene_options("state")?, answers)?)
}

fn scene(query: &str) -> Answer {
    let q = parse(query, &[&SCENE_PARAMETERS])?;
    let t = std::time::Instant::now();
    let view = view_of(&q, Answers::All)?;
    let (state, domains) = rayon::join(
        || views::screen_svg(&view.state_figure()?),
        || {
            view.domains_figure()
                .map(|f| views::screen_svg(&f))
                .transpose()
        },
    );
    let (state, domains) = (state?, domains?);
    let mut v = view.json();
    v["svg"] = json!({ "state": state, "domains": domains });
    v["elapsed_ms"] = json!(t.elapsed().as_secs_f64() * 1e3);
    Ok(Reply::json(&v))
}

fn mechanism(query: &str) -> Answer {
    let q = parse(query, &[&SCENE_PARAMETERS])?;
    let view = view_of(&q, Answers::Limit)?;
    let frames = view.mechanism_frames();
    let svgs = frames
        .iter()
        .map(views::screen_svg)
        .collect::<anyhow::Result<Vec<_>>>()?;
    Ok(Reply::json(&json!({
        "title": frames.first().map(|f| f.title.clone()),
        "frames": svgs,
        "limit": view.limit,
    })))
}

fn map_of(q: &Query) -> Result<(super::map::MapView, FigureSpec), Failure> {
    let options = q.scene_options("state")?;
    let scene = views::state_scene(&options)?;
    let window = MapWindow::of_query(q, &scene)?;
    Ok(super::map::regime_map(&options, &scene, &window)?)
}

fn map(query: &str) -> Answer {
    let q = parse(query, &[&SCENE_PARAMETERS, &MAP_PARAMETERS])?;
    let t = std::time::Instant::now();
    let (view, _) = map_of(&q)?;
    let mut v = json!(view);
    v["elapsed_ms"] = json!(t.elapsed().as_secs_f64() * 1e3);
    Ok(Reply::json(&v))
}

fn study(query: &str) -> Answer {
    let q = parse(query, &[&SCENE_PARAMETERS, &MAP_PARAMETERS])?;
    let options = q.scene_options("state")?;
    let scene = views::state_scene(&options)?;
    let window = MapWindow::of_query(&q, &scene)?;
    let mut r = Reply::ok(
        "text/yaml; charset=utf-8",
        manifest_text(&options, &scene, &window),
    );
    r.download = Some("explore-around-scene.yaml".into());
    Ok(r)
}

fn figure(query: &str, app: &App) -> Answer {
    let q = parse(
        query,
        &[&SCENE_PARAMETERS, &MAP_PARAMETERS, &FIGURE_PARAMETERS],
    )?;
    let pdf = match q.get("format").unwrap_or("svg") {
        "svg" => false,
        "pdf" => true,
        other => return Err(QueryError::new("format", other, "svg or pdf").into()),
    };
    let view = q.get("view").unwrap_or("state");
    let spec = match view {
        "state" => view_of(&q, Answers::All)?.state_figure()?,
        "domains" => view_of(&q, Answers::All)?.domains_figure().ok_or_else(|| {
            QueryError::new(
                "view",
                "domains",
                "Fig. 2 is drawn for a circular arch with radial joints under self-weight",
            )
        })?,
        "mechanism" => view_of(&q, Answers::Limit)?
            .mechanism_frames()
            .pop()
            .ok_or_else(|| QueryError::new("view", "mechanism", "a scene with a limit state"))?,
        "map" => map_of(&q)?.1,
        "run" => app
            .run
            .as_ref()
            .and_then(|r| r.figure().cloned())
            .ok_or_else(|| Failure::NotFound("no run directory with a figure was opened".into()))?,
        other => {
            return Err(
                QueryError::new("view", other, "state, domains, mechanism, map or run").into(),
            );
        }
    };
    let bytes = views::download(&spec, pdf)?;
    let ext = if pdf { "pdf" } else { "svg" };
    let mut r = Reply::ok(
        if pdf {
            "application/pdf"
        } else {
            "image/svg+xml"
        },
        bytes,
    );
    r.download = Some(format!("{view}.{ext}"));
    Ok(r)
}

fn run(query: &str, app: &App) -> Answer {
    parse(query, &[])?;
    Ok(Reply::json(&match &app.run {
        Some(run) => run.json(),
        None => json!({ "open": false }),
    }))
}

/// The query of `archstudy.solve` keywords that gives a solution's scene.
pub(crate) fn scene_query(s: &Solution) -> String {
    let mut p: Vec<(&str, String)> = Vec::new();
    if let Some(k) = s.k {
        p.push(("k", k.to_string()));
    }
    p.push((
        "mu",
        match s.mu {
            Some(m) if !s.mu_infinite => m.to_string(),
            _ => "inf".into(),
        },
    ));
    p.push(("half_angle", s.half_angle_deg.to_string()));
    p.push(("weight", s.weight.as_str().into()));
    if let Some(n) = s.voussoirs {
        p.push(("voussoirs", n.to_string()));
    }
    p.push(("shape", s.shape.into()));
    if let Some(e) = s.eccentricity {
        p.push(("eccentricity", e.to_string()));
    }
    p.push(("joints", s.joints.into()));
    if s.keystone && (s.voussoirs.is_some() || s.shape == "pointed") {
        p.push(("keystone", "true".into()));
    }
    p.push(("load", s.load.into()));
    if let Some(a) = s.at_deg {
        p.push(("at", a.to_string()));
    }
    if s.load != "self_weight" {
        // A load_factor case gives no λ: its scene is shown at its λ_max.
        let l = s.lambda.or(s.load_factor).unwrap_or(0.0);
        p.push(("lambda", l.to_string()));
    }
    p.iter()
        .map(|(n, v)| format!("{n}={v}"))
        .collect::<Vec<_>>()
        .join("&")
}

fn case(query: &str, app: &App) -> Answer {
    let q = parse(query, &[&CASE_PARAMETERS])?;
    let run = app.run.as_ref().ok_or_else(|| {
        Failure::NotFound("no run directory was given to archstudy explore".into())
    })?;
    let id = match q.integer("case")? {
        Some(id) => u64::try_from(id)
            .map_err(|_| QueryError::new("case", &id.to_string(), "a case id ≥ 0"))?,
        None => {
            let panel = q.integer("panel")?.unwrap_or(0);
            let panel = usize::try_from(panel)
                .map_err(|_| QueryError::new("panel", &panel.to_string(), "a panel ≥ 0"))?;
            let need = |n: &str| {
                q.number(n, false)?
                    .ok_or_else(|| QueryError::new(n, "", "a number: the point clicked"))
            };
            run.case_at(panel, need("x")?, need("y")?)?
        }
    };
    let (mut v, sol) = run.case(id)?;
    v["query"] = json!(scene_query(&sol));
    v["solution"] = json!(sol);
    Ok(Reply::json(&v))
}

/// A file of the run directory: a relative path of plain components that resolves, links
/// followed, to a regular file inside the directory.
fn run_file(rel: &str, app: &App) -> Reply {
    let not_found = || Reply::error(StatusCode::NOT_FOUND, "no such file in the run directory");
    let Some(run) = &app.run else {
        return Reply::error(StatusCode::NOT_FOUND, "no run directory was given");
    };
    let Ok(q) = Query::parse(&format!("p={rel}"), &[&["p"]]) else {
        return not_found();
    };
    let Some(rel) = q.get("p") else {
        return not_found();
    };
    let plain = Path::new(rel)
        .components()
        .all(|c| matches!(c, std::path::Component::Normal(_)));
    if !plain || rel.contains('\\') || rel.contains('\0') {
        return Reply::error(
            StatusCode::BAD_REQUEST,
            "a path inside the run directory, without '..', a root or a backslash",
        );
    }
    let Ok(full) = run.dir.join(rel).canonicalize() else {
        return not_found();
    };
    let inside = full.starts_with(&run.dir);
    let Ok(meta) = std::fs::metadata(&full) else {
        return not_found();
    };
    if !inside || !meta.is_file() || meta.len() > MAX_FILE_BYTES {
        return not_found();
    }
    let Ok(bytes) = std::fs::read(&full) else {
        return not_found();
    };
    let content_type = match full.extension().and_then(|e| e.to_str()).unwrap_or("") {
        "png" => "image/png",
        "svg" => "image/svg+xml",
        "pdf" => "application/pdf",
        "html" => "text/html; charset=utf-8",
        "json" => "application/json",
        "md" | "csv" | "tex" | "yaml" | "txt" => "text/plain; charset=utf-8",
        _ => "application/octet-stream",
    };
    Reply::ok(content_type, bytes)
}
