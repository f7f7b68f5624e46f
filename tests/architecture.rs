//! The module graph: data flows one way, and only the command-line module sees clap.
//! Read from the sources, so a new upward import fails here rather than in review.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// The top-level modules of the library, lowest first. A module may use the modules before
/// it, never one after it (docs/architecture.md says what each owns).
const LAYERS: [&str; 27] = [
    "error",
    "progress",
    "provenance",
    "output",
    "model",
    "sampling",
    "analysis",
    "scene",
    "manifest",
    "citation",
    "plan",
    "engine",
    "records",
    "store",
    "boundaries",
    "figdata",
    "plot",
    "report",
    "runner",
    "shard",
    "merge",
    "slurm",
    "archive",
    "verify",
    "explore",
    "app",
    "lib",
];

fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            sources(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// The top-level module a source file belongs to (`lib` for lib.rs, `main` for main.rs).
fn module_of(file: &Path) -> String {
    let rel = file.strip_prefix(src()).unwrap();
    let first = rel
        .components()
        .next()
        .unwrap()
        .as_os_str()
        .to_string_lossy();
    first.trim_end_matches(".rs").to_string()
}

/// The top-level modules a piece of source names as `crate::X`, including inside
/// `use crate::{X, Y::Z}` groups.
fn crate_imports(text: &str) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    for (i, _) in text.match_indices("crate::") {
        let rest = &text[i + "crate::".len()..];
        if let Some(group) = rest.strip_prefix('{') {
            let end = group.find('}').unwrap_or(group.len());
            for item in group[..end].split(',') {
                let name: String = item
                    .trim()
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                if !name.is_empty() {
                    out.insert(name);
                }
            }
        } else {
            let name: String = rest
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            out.insert(name);
        }
    }
    out
}

/// Source text without comments, so that doc links and prose do not count as imports.
fn code_of(text: &str) -> String {
    text.lines()
        .filter(|l| !l.trim_start().starts_with("//"))
        .collect::<Vec<_>>()
        .join("\n")
}

fn layer(module: &str) -> usize {
    LAYERS
        .iter()
        .position(|m| *m == module)
        .unwrap_or_else(|| panic!("module `{module}` is not in LAYERS: place it there"))
}

#[test]
fn every_import_points_down_the_data_flow() {
    let mut files = Vec::new();
    sources(&src(), &mut files);
    let mut upward = Vec::new();
    for f in &files {
        let module = module_of(f);
        if module == "main" {
            continue;
        }
        let own = layer(&module);
        let code = code_of(&std::fs::read_to_string(f).unwrap());
        for used in crate_imports(&code) {
            if used == module || used == "self" || used == "super" {
                continue;
            }
            if layer(&used) > own {
                upward.push(format!("{} uses crate::{used}", f.display()));
            }
        }
    }
    assert!(
        upward.is_empty(),
        "imports against the data flow:\n{}",
        upward.join("\n")
    );
}

#[test]
fn only_the_command_line_module_names_clap() {
    let mut files = Vec::new();
    sources(&src(), &mut files);
    let app = src().join("app");
    let offenders: Vec<String> = files
        .iter()
        .filter(|f| !f.starts_with(&app) && !f.ends_with("main.rs"))
        .filter(|f| code_of(&std::fs::read_to_string(f).unwrap()).contains("clap"))
        .map(|f| f.display().to_string())
        .collect();
    assert!(
        offenders.is_empty(),
        "clap named outside src/app and src/main.rs: {offenders:?}"
    );
}

#[test]
fn the_import_reader_sees_groups_and_paths() {
    let found = crate_imports("use crate::{model::Arch, scene};\nlet x = crate::store::read();");
    let want: BTreeSet<String> = ["model", "scene", "store"].map(String::from).into();
    assert_eq!(found, want);
}
