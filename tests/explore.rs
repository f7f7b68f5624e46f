//! `archstudy explore`'s server alone: every bad query answered 400 naming its parameter, no
//! file outside the run directory, oversized maps refused, 200 concurrent requests answered
//! with the library's own values, the paper's bifurcations on the map around its scene, and
//! a click on a run's map giving the case there.

use crate::common::{archstudy, run_study, scratch};
use archstudy::explore::{ExploreOptions, Explorer, start};
use archstudy::manifest::SceneOptions;
use serde_json::Value;
use std::io::{Read, Write};
use std::net::TcpStream;
use std::path::Path;

fn server(run_dir: Option<&Path>) -> Explorer {
    start(&ExploreOptions {
        run_dir: run_dir.map(Path::to_path_buf),
        host: "127.0.0.1".into(),
        port: 0,
    })
    .unwrap()
}

/// One request on a fresh connection: the status and the body.
fn request(s: &Explorer, method: &str, target: &str) -> (u16, Vec<u8>) {
    let mut c = TcpStream::connect(s.addr()).unwrap();
    write!(
        c,
        "{method} {target} HTTP/1.1\r\nHost: {}\r\nConnection: close\r\n\r\n",
        s.addr()
    )
    .unwrap();
    let mut raw = Vec::new();
    c.read_to_end(&mut raw).unwrap();
    let split = raw.windows(4).position(|w| w == b"\r\n\r\n").unwrap();
    let head = String::from_utf8_lossy(&raw[..split]).to_string();
    let status = head.split(' ').nth(1).unwrap().parse().unwrap();
    (status, raw[split + 4..].to_vec())
}

fn get_json(s: &Explorer, target: &str) -> (u16, Value) {
    let (status, body) = request(s, "GET", target);
    (status, serde_json::from_slice(&body).unwrap_or(Value::Null))
}

#[test]
fn every_bad_query_is_a_400_naming_the_parameter_and_the_value() {
    let s = server(None);
    let cases = [
        ("/api/scene?k=abc", "k", "abc"),
        ("/api/scene?k=0.9", "k", "0.9"),
        ("/api/scene?k=inf", "k", "inf"),
        ("/api/scene?t_over_r=3", "t_over_r", "3"),
        ("/api/scene?k=1.2&t_over_r=0.2", "t_over_r", "0.2"),
        ("/api/scene?mu=-1", "mu", "-1"),
        ("/api/scene?half_angle=200", "half_angle", "200"),
        ("/api/scene?weight=heavy", "weight", "heavy"),
        ("/api/scene?voussoirs=0", "voussoirs", "0"),
        ("/api/scene?voussoirs=100000", "voussoirs", "100000"),
        ("/api/scene?voussoirs=many", "voussoirs", "many"),
        ("/api/scene?shape=square", "shape", "square"),
        (
            "/api/scene?shape=pointed&eccentricity=1.5",
            "eccentricity",
            "1.5",
        ),
        ("/api/scene?joints=diagonal", "joints", "diagonal"),
        ("/api/scene?keystone=maybe", "keystone", "maybe"),
        ("/api/scene?load=wind", "load", "wind"),
        ("/api/scene?load=point&at=200&lambda=0.1", "at", "200"),
        ("/api/scene?load=point&at_x=2&lambda=0.1", "at_x", "2"),
        ("/api/scene?load=horizontal&lambda=-1", "lambda", "-1"),
        ("/api/scene?colour=red", "colour", "red"),
        ("/api/scene?k=1.2&k=1.3", "k", "1.3"),
        ("/api/scene?mu=%zz", "mu", "%zz"),
        ("/api/mechanism?half_angle=0", "half_angle", "0"),
        ("/api/map?k_steps=1", "k_steps", "1"),
        ("/api/map?k_from=2&k_to=1.5", "k_from", "2"),
        ("/api/map?mu_from=-1", "mu_from", "-1"),
        ("/api/map?mu_steps=x", "mu_steps", "x"),
        ("/api/figure?view=elevation", "view", "elevation"),
        ("/api/figure?format=png", "format", "png"),
        ("/api/study?k=1.2&k_to=999", "k_from", "999"),
        ("/api/run?x=1", "x", "1"),
    ];
    for (target, parameter, value) in cases {
        let (status, v) = get_json(&s, target);
        assert_eq!(status, 400, "{target}: {v}");
        assert_eq!(v["parameter"], parameter, "{target}: {v}");
        assert!(
            v["value"].as_str().unwrap().contains(value),
            "{target}: {v}"
        );
        let allowed = v["allowed"].as_str().unwrap();
        assert!(allowed.len() > 5, "{target}: says what is allowed: {v}");
        assert!(v["error"].as_str().unwrap().contains(parameter), "{target}");
    }
    s.stop();
}

#[test]
fn the_scene_answer_is_the_librarys_and_its_figures_are_drawn() {
    let s = server(None);
    let (status, v) = get_json(&s, "/api/scene?k=1.15&mu=0.35");
    assert_eq!(status, 200, "{v}");
    // Between K_c(∞) = 1.1136 and K_c(0.35) = 1.1643 the arch does not stand: mixed.
    assert_eq!(v["state"]["regime"], "mixed");
    assert_eq!(v["stands"], false);
    let want = archstudy::scene::solve(
        &SceneOptions {
            find: "thickness".into(),
            mu: 0.35,
            ..SceneOptions::default()
        }
        .scene()
        .unwrap(),
    );
    let kc = v["finds"]["thickness"]["k_crit"].as_f64().unwrap();
    assert_eq!(Some(kc), want.k_crit);
    assert!((kc - 1.164_335_8).abs() < 1e-6, "K_c(0.35) = {kc}");
    // The drawn joints are the limit state's: three hinges and two sliding springings.
    let drawn = &v["drawn_joints"];
    assert_eq!(drawn["hinges"].as_array().unwrap().len(), want.hinges.len());
    assert_eq!(
        drawn["sliding_joints"].as_array().unwrap().len(),
        want.sliding_joints.len()
    );
    for (h, w) in drawn["hinges"].as_array().unwrap().iter().zip(&want.hinges) {
        assert_eq!(h["angle_deg"].as_f64().unwrap(), w.angle_deg);
    }
    assert!(v["svg"]["state"].as_str().unwrap().starts_with("<svg"));
    assert!(v["svg"]["domains"].as_str().unwrap().contains("Domains"));
    // The thresholds of the semicircle (the paper's values).
    let t = &v["finds"]["thresholds"];
    assert!(
        (t["k_c_rotational"].as_f64().unwrap() - 1.1136).abs() < 1e-4,
        "{t}"
    );
    assert!((t["mu_min"].as_f64().unwrap() - 0.309).abs() < 1e-3, "{t}");
    // Another form has no Fig. 2, and says so by leaving it out.
    let (status, v) = get_json(
        &s,
        "/api/scene?k=1.3&mu=0.6&shape=pointed&eccentricity=0.2&load=horizontal&lambda=0.05",
    );
    assert_eq!(status, 200, "{v}");
    assert!(v["svg"]["domains"].is_null());
    // μ_min at this K: the friction find at a μ just above it stands on its sliding rows.
    let mu_min = v["mu_min_at_k"].as_f64().unwrap();
    assert!(mu_min > 0.0 && mu_min <= v["finds"]["friction"]["mu_crit"].as_f64().unwrap() + 1e-9);
    assert!(v["finds"]["load_factor"]["load_factor"].as_f64().unwrap() > 0.05);
    // The mechanism moves through its frames, from rest.
    let (status, m) = get_json(&s, "/api/mechanism?k=1.1&mu=0.35");
    assert_eq!(status, 200);
    let frames = m["frames"].as_array().unwrap();
    assert_eq!(frames.len(), archstudy::explore::views::MECHANISM_FRAMES);
    assert!(
        frames
            .iter()
            .all(|f| f.as_str().unwrap().starts_with("<svg"))
    );
    assert_ne!(frames[0], frames[frames.len() - 1], "the blocks move");
    s.stop();
}

#[test]
fn a_scene_in_the_gap_shows_its_collapse_and_says_where_it_stands() {
    // Twelve voussoirs under a horizontal load: static limit λ_max = 8.518042, collapse (the
    // first complete solution) at λ = 7.383083: left springing hinging at the intrados and
    // sliding inward, the first joint sliding outward, the right springing hinging at the
    // extrados.
    let s = server(None);
    let scene = "k=1.5278&mu=1.0396&half_angle=50.367&voussoirs=12&load=horizontal";
    let (status, v) = get_json(&s, &format!("/api/scene?{scene}&lambda=9"));
    assert_eq!(status, 200, "{v}");
    assert_eq!(v["stands"], false);
    let lf = &v["finds"]["load_factor"];
    assert!(
        (lf["collapse_value"].as_f64().unwrap() - 7.383083).abs() < 1e-6,
        "{lf}"
    );
    let drawn = &v["drawn_joints"];
    assert_eq!(drawn["hinges"], lf["collapse_hinges"]);
    assert_eq!(drawn["sliding_joints"], lf["collapse_sliding_joints"]);
    let hinges: Vec<(f64, &str)> = drawn["hinges"]
        .as_array()
        .unwrap()
        .iter()
        .map(|h| {
            (
                h["angle_deg"].as_f64().unwrap(),
                h["face"].as_str().unwrap(),
            )
        })
        .collect();
    assert_eq!(hinges, [(-50.367, "intrados"), (50.367, "extrados")]);
    let senses: Vec<&str> = drawn["sliding_joints"]
        .as_array()
        .unwrap()
        .iter()
        .map(|j| j["sense"].as_str().unwrap())
        .collect();
    assert_eq!(senses, ["inward", "outward"]);
    assert!(
        v["drawn"]
            .as_str()
            .unwrap()
            .contains("first complete solution")
    );
    assert!(
        v["svg"]["state"]
            .as_str()
            .unwrap()
            .contains("collapse λ = 7.3831")
    );
    // At λ = 8 an equilibrium exists, but the arch can already move: the page says so.
    let (_, v) = get_json(&s, &format!("/api/scene?{scene}&lambda=8"));
    assert_eq!(v["stands"], true);
    assert!(
        v["drawn"].as_str().unwrap().contains("inside the gap"),
        "{}",
        v["drawn"]
    );
    let (_, v) = get_json(&s, &format!("/api/scene?{scene}&lambda=7"));
    assert!(
        !v["drawn"].as_str().unwrap().contains("gap"),
        "{}",
        v["drawn"]
    );
    // The mechanism that moves is the collapse's.
    let (_, m) = get_json(&s, &format!("/api/mechanism?{scene}&lambda=9"));
    assert!(
        m["title"].as_str().unwrap().contains("at the collapse"),
        "{}",
        m["title"]
    );
    s.stop();
}

#[test]
fn the_map_around_the_papers_scene_locates_both_bifurcations() {
    let s = server(None);
    let (status, v) = get_json(
        &s,
        "/api/map?k=1.2&mu=0.35&k_from=1.05&k_to=1.35&mu_from=0.2&mu_to=0.6",
    );
    assert_eq!(status, 200, "{v}");
    let bifs = v["bifurcations"].as_array().unwrap();
    let near = |mu: f64, k: f64| {
        bifs.iter().any(|b| {
            (b[0].as_f64().unwrap() - mu).abs() < 1e-3 && (b[1].as_f64().unwrap() - k).abs() < 1e-3
        })
    };
    assert!(near(0.3953, 1.1136), "rotational/mixed: {bifs:?}");
    assert!(near(0.3092, 1.2205), "mixed/sliding: {bifs:?}");
    // The frame maps the plotting area to the window drawn.
    let f = &v["frame"];
    assert_eq!(f["x"][0].as_f64(), Some(0.2));
    assert_eq!(f["y"][1].as_f64(), Some(1.35));
    assert!(f["left"].as_f64().unwrap() < f["right"].as_f64().unwrap());
    // Every located collapse point lies on K_c(μ) (a K-edge) or on μ_c(K) (a μ-edge).
    let solved = |find: &str, k: Option<f64>, mu: f64| {
        archstudy::scene::solve_static(
            &SceneOptions {
                find: find.into(),
                k,
                mu,
                ..SceneOptions::default()
            }
            .scene()
            .unwrap(),
        )
    };
    let collapse = v["collapse"].as_array().unwrap();
    assert!(collapse.len() >= 20, "{}", collapse.len());
    for c in collapse {
        let (mu, k) = (c[0].as_f64().unwrap(), c[1].as_f64().unwrap());
        let kc = solved("thickness", None, mu).k_crit.unwrap();
        let muc = solved("friction", Some(k), f64::INFINITY)
            .mu_crit
            .unwrap_or(f64::NAN);
        assert!(
            (k - kc).abs() < 1e-6 || (mu - muc).abs() < 1e-6,
            "({mu}, {k}): K_c(μ) = {kc}, μ_c(K) = {muc}"
        );
    }
    // Oversized maps are refused before any work, naming the steps.
    let (status, v) = get_json(&s, "/api/map?k=1.2&mu=0.35&k_steps=101&mu_steps=101");
    assert_eq!(status, 400);
    assert_eq!(v["parameter"], "k_steps");
    let (status, v) = get_json(
        &s,
        "/api/map?k=1.3&mu=0.6&shape=pointed&eccentricity=0.2&k_steps=30&mu_steps=30",
    );
    assert_eq!(status, 400, "{v}");
    assert!(v["allowed"].as_str().unwrap().contains("441"), "{v}");
    // The study of the map is a manifest of the same window.
    let (status, text) = request(&s, "GET", "/api/study?k=1.2&mu=0.35");
    assert_eq!(status, 200);
    let text = String::from_utf8(text).unwrap();
    let m = archstudy::manifest::parse(&text, Path::new("explore.yaml")).unwrap();
    assert_eq!(archstudy::plan::case_count(&m), 31 * 31);
    s.stop();
}

#[test]
fn two_hundred_concurrent_requests_are_answered_with_the_librarys_values() {
    let s = server(None);
    let ks: Vec<f64> = (0..200).map(|i| 1.05 + 0.002 * f64::from(i)).collect();
    let answers: Vec<(u16, Value)> = std::thread::scope(|scope| {
        let handles: Vec<_> = ks
            .iter()
            .map(|k| {
                let s = &s;
                scope.spawn(move || get_json(s, &format!("/api/scene?k={k}&mu=0.35")))
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    for (k, (status, v)) in ks.iter().zip(&answers) {
        assert_eq!(*status, 200, "K = {k}: {v}");
        let want = archstudy::scene::solve(
            &SceneOptions {
                k: Some(*k),
                mu: 0.35,
                ..SceneOptions::default()
            }
            .scene()
            .unwrap(),
        );
        assert_eq!(
            v["state"]["regime"],
            want.regime.unwrap().as_str(),
            "K = {k}"
        );
        assert_eq!(v["state"]["k"].as_f64(), Some(*k));
    }
    s.stop();
}

#[test]
fn no_file_outside_the_run_directory_is_served() {
    let dir = scratch("explore-files");
    let run = run_study(
        &dir,
        "small.yaml",
        "name: small\ngrid:\n  k: {from: 1.05, to: 1.5, steps: 11}\n  mu: {from: 0.2, to: 0.8, steps: 11}\nload_cases:\n  - {name: gravity, kind: self_weight}\nfind: state\n",
    );
    std::fs::write(dir.join("secret.txt"), "not for the page").unwrap();
    #[cfg(unix)]
    std::os::unix::fs::symlink(dir.join("secret.txt"), run.join("link.txt")).unwrap();
    let s = server(Some(&run));
    let (status, body) = request(&s, "GET", "/run/run.json");
    assert_eq!(status, 200);
    assert_eq!(body, std::fs::read(run.join("run.json")).unwrap());
    for target in [
        "/run/../secret.txt",
        "/run/%2e%2e/secret.txt",
        "/run/plots/..%2f..%2fsecret.txt",
        "/run//etc/passwd",
        "/run/%2fetc%2fpasswd",
        "/run/..%5csecret.txt",
        "/run/link.txt",
        "/run/plots",
        "/run/nothing-here",
        "/run/",
    ] {
        let (status, body) = request(&s, "GET", target);
        assert!(status == 400 || status == 404, "{target}: {status}");
        assert!(
            !String::from_utf8_lossy(&body).contains("not for the page"),
            "{target}"
        );
    }
    // A click on the run's map gives the case under it, its stored row and its scene.
    let (status, v) = get_json(&s, "/api/run/case?panel=0&x=0.44&y=1.23");
    assert_eq!(status, 200, "{v}");
    let stored = &v["stored"];
    assert!((stored["k"].as_f64().unwrap() - 1.23).abs() < 1e-12, "{v}");
    assert!((stored["mu"].as_f64().unwrap() - 0.44).abs() < 1e-12, "{v}");
    assert_eq!(
        stored["regime"], v["solution"]["regime"],
        "solved again alike"
    );
    let (status, v) = get_json(&s, "/api/run/case?case=100000");
    assert_eq!((status, v["parameter"].as_str()), (400, Some("case")));
    let (status, v) = get_json(&s, "/api/run");
    assert_eq!(status, 200);
    assert_eq!(v["figure"]["kind"], "regime_map");
    assert_eq!(v["cases"], 121);
    s.stop();
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_server_is_read_only_and_bounds_its_requests() {
    let s = server(None);
    assert_eq!(request(&s, "POST", "/api/scene").0, 405);
    // A page elsewhere whose name is rebound to this machine is not answered.
    let mut c = TcpStream::connect(s.addr()).unwrap();
    write!(
        c,
        "GET /api/run HTTP/1.1\r\nHost: attacker.example:{}\r\nConnection: close\r\n\r\n",
        s.addr().port()
    )
    .unwrap();
    let mut raw = String::new();
    c.read_to_string(&mut raw).unwrap();
    assert!(raw.starts_with("HTTP/1.1 421"), "{raw}");
    // Windows too narrow to draw, or a μ too large for a window around it, are refused by
    // the parameter given (the scene's μ when no window was).
    let (status, v) = get_json(&s, "/api/map?k=1.2&mu=0.4&mu_from=0&mu_to=1e-10");
    assert_eq!(
        (status, v["parameter"].as_str()),
        (400, Some("mu_from")),
        "{v}"
    );
    let (status, v) = get_json(&s, "/api/map?k=1.2&mu=0.4&k_from=1.2&k_to=1.2000000001");
    assert_eq!(
        (status, v["parameter"].as_str()),
        (400, Some("k_from")),
        "{v}"
    );
    let (status, v) = get_json(&s, "/api/map?k=1.2&mu=1e17");
    assert_eq!((status, v["parameter"].as_str()), (400, Some("mu")), "{v}");
    assert_eq!(request(&s, "DELETE", "/").0, 405);
    let (status, body) = request(&s, "HEAD", "/");
    assert_eq!((status, body.len()), (200, 0));
    let (status, body) = request(&s, "GET", "/");
    assert_eq!(status, 200);
    assert!(String::from_utf8_lossy(&body).contains("archstudy explore"));
    assert_eq!(request(&s, "GET", "/app.js").0, 200);
    assert_eq!(request(&s, "GET", "/etc/passwd").0, 404);
    let (status, v) = get_json(&s, "/api/run");
    assert_eq!(
        (status, &v["open"]),
        (200, &Value::Bool(false)),
        "no run directory given"
    );
    assert_eq!(request(&s, "GET", "/api/figure?view=run").0, 404);
    let long = format!("/api/scene?k=1.2{}", "&x=1".repeat(3000));
    let status = request(&s, "GET", &long).0;
    assert!(status == 414 || status == 431 || status == 400, "{status}");
    let (status, pdf) = request(&s, "GET", "/api/figure?view=state&format=pdf&k=1.2&mu=0.4");
    assert_eq!(status, 200);
    assert!(pdf.starts_with(b"%PDF"));
    let (status, svg) = request(&s, "GET", "/api/figure?view=domains&k=1.2&mu=0.4");
    assert_eq!(status, 200);
    assert!(svg.starts_with(b"<svg"));
    s.stop();
}

#[test]
fn the_command_prints_its_address_and_warns_off_loopback() {
    use std::io::BufRead;
    let mut child = crate::common::bin()
        .args(["explore", "--port", "0", "--host", "0.0.0.0"])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut line = String::new();
    std::io::BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    child.kill().unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(
        line.starts_with("archstudy explore: serving http://0.0.0.0:"),
        "{line}"
    );
    assert!(String::from_utf8_lossy(&out.stderr).contains("warning: listening on 0.0.0.0"));
    // A port in use and a host that is no address are refused by name, before serving.
    let taken = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let port = taken.local_addr().unwrap().port().to_string();
    let o = archstudy(&["explore", "--port", &port]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("'--port'"));
    let o = archstudy(&["explore", "--port", "0", "--host", "no such host"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("'--host'"));
    let o = archstudy(&["explore", "/no/such/run"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("/no/such/run"));
}

#[test]
fn a_click_on_an_influence_line_gives_the_case_under_it() {
    let dir = scratch("explore-influence");
    let run = run_study(
        &dir,
        "influence.yaml",
        "name: influence\narch: {shape: pointed, eccentricity: 0.2}\ngrid:\n  at_x: {values: [0.1, 0.25, 0.4, 0.6, 0.75, 0.9]}\n  k: {values: [1.3]}\n  mu: {values: [0.5]}\nload_cases:\n  - {name: point, kind: point}\nfind: load_factor\n",
    );
    let s = server(Some(&run));
    let (status, v) = get_json(&s, "/api/run");
    assert_eq!(status, 200, "{v}");
    assert_eq!(v["figure"]["kind"], "lines", "{v}");
    let frames = v["figure"]["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 2, "λ against the angle and against x/L");
    for id in 0..6_u64 {
        let (_, c) = get_json(&s, &format!("/api/run/case?case={id}"));
        let lambda = c["stored"]["load_factor"].as_f64().unwrap();
        let at_x = c["solution"]["at_x"].as_f64().unwrap();
        // The panel against x/L: the point (x/L, λ_max) of the case is that case.
        let y = if frames[1]["log_y"].as_bool().unwrap() {
            lambda.log10()
        } else {
            lambda
        };
        let (status, hit) = get_json(&s, &format!("/api/run/case?panel=1&x={at_x}&y={y}"));
        assert_eq!(status, 200, "{hit}");
        assert_eq!(
            hit["case_id"].as_u64(),
            Some(id),
            "x/L = {at_x}, λ = {lambda}"
        );
        // Its scene, solved again, has the stored λ_max.
        let again = hit["solution"]["load_factor"].as_f64().unwrap();
        assert!(
            (again - lambda).abs() <= 1e-9 * lambda.max(1.0),
            "{again} vs {lambda}"
        );
    }
    s.stop();
    let _ = std::fs::remove_dir_all(&dir);
}
