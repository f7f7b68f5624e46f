//! The citation metadata of a run: ro-crate-metadata.json describes every file the run wrote.

use crate::common::{run_study, scratch};
use std::collections::BTreeMap;

const STUDY: &str = "name: cited
title: A cited study
description: Thresholds of the semicircle.
authors:
  - {name: Ada Lovelace, orcid: 0000-0002-1825-0097, affiliation: Analytical Engines}
license: CC-BY-4.0
grid:
  k: {values: [1.1, 1.2, 1.3]}
  mu: {values: [0.3, 0.5]}
";

#[test]
fn the_run_directory_carries_an_ro_crate_of_every_file() {
    let dir = scratch("citation");
    let run = run_study(&dir, "cited.yaml", STUDY);
    let text = std::fs::read_to_string(run.join("ro-crate-metadata.json")).unwrap();
    let c: serde_json::Value = serde_json::from_str(&text).unwrap();
    let graph = c["@graph"].as_array().unwrap();
    let files: BTreeMap<String, u64> = graph
        .iter()
        .filter(|e| e["@type"] == "File")
        .map(|e| {
            let size = e["contentSize"].as_str().unwrap().parse().unwrap();
            (e["@id"].as_str().unwrap().to_string(), size)
        })
        .collect();
    // Every file on disk is listed with its size, and nothing else is.
    let mut on_disk = BTreeMap::new();
    for rel in [
        "manifest.yaml",
        "run.json",
        "results.parquet",
        "report.html",
        "report.md",
    ] {
        on_disk.insert(
            rel.to_string(),
            std::fs::metadata(run.join(rel)).unwrap().len(),
        );
    }
    for e in std::fs::read_dir(run.join("plots")).unwrap() {
        let p = e.unwrap().path();
        let rel = format!("plots/{}", p.file_name().unwrap().to_string_lossy());
        on_disk.insert(rel, std::fs::metadata(&p).unwrap().len());
    }
    for (rel, size) in &on_disk {
        assert_eq!(files.get(rel), Some(size), "{rel}");
    }
    let total_on_disk = walk_count(&run) - 1; // the crate metadata does not list itself
    assert_eq!(files.len(), total_on_disk);
    let dataset = graph.iter().find(|e| e["@id"] == "./").unwrap();
    assert_eq!(dataset["name"], "A cited study");
    assert_eq!(dataset["description"], "Thresholds of the semicircle.");
    assert_eq!(dataset["license"], "CC-BY-4.0");
    let author = graph
        .iter()
        .find(|e| e["@id"] == "https://orcid.org/0000-0002-1825-0097")
        .unwrap();
    assert_eq!(author["name"], "Ada Lovelace");
    assert_eq!(author["affiliation"], "Analytical Engines");
    let run_json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(run.join("run.json")).unwrap()).unwrap();
    assert_eq!(dataset["datePublished"], run_json["finished_at"]);
}

/// Every file of the run directory (but the crate itself) with its size, walked.
fn sizes_on_disk(dir: &std::path::Path, rel: &str, out: &mut BTreeMap<String, u64>) {
    for e in std::fs::read_dir(dir.join(rel)).unwrap() {
        let p = e.unwrap().path();
        let name = p.file_name().unwrap().to_string_lossy().to_string();
        let r = if rel.is_empty() {
            name
        } else {
            format!("{rel}/{name}")
        };
        if p.is_dir() {
            sizes_on_disk(dir, &r, out);
        } else if r != "ro-crate-metadata.json" {
            out.insert(r, std::fs::metadata(&p).unwrap().len());
        }
    }
}

/// The files the crate lists, with their sizes.
fn sizes_in_crate(run: &std::path::Path) -> BTreeMap<String, u64> {
    let text = std::fs::read_to_string(run.join("ro-crate-metadata.json")).unwrap();
    let c: serde_json::Value = serde_json::from_str(&text).unwrap();
    c["@graph"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|e| e["@type"] == "File")
        .map(|e| {
            let size = e["contentSize"].as_str().unwrap().parse().unwrap();
            (e["@id"].as_str().unwrap().to_string(), size)
        })
        .collect()
}

#[test]
fn report_describes_the_files_it_drew_again() {
    let dir = scratch("citation-report");
    let run = run_study(&dir, "cited.yaml", STUDY);
    // A crate whose sizes no longer match, and a report file gone: `report` draws them again.
    let text = std::fs::read_to_string(run.join("ro-crate-metadata.json")).unwrap();
    std::fs::write(
        run.join("ro-crate-metadata.json"),
        text.replace("\"contentSize\": \"", "\"contentSize\": \"9"),
    )
    .unwrap();
    std::fs::remove_file(run.join("report.md")).unwrap();
    let o = crate::common::archstudy(&["report", run.to_str().unwrap()]);
    assert!(o.status.success(), "{}", crate::common::stderr(&o));
    let mut on_disk = BTreeMap::new();
    sizes_on_disk(&run, "", &mut on_disk);
    assert!(on_disk.contains_key("report.md") && on_disk.len() > 10);
    assert_eq!(sizes_in_crate(&run), on_disk);
    let _ = std::fs::remove_dir_all(&dir);
}

fn walk_count(dir: &std::path::Path) -> usize {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let p = e.unwrap().path();
            if p.is_dir() { walk_count(&p) } else { 1 }
        })
        .sum()
}

#[test]
fn a_bad_orcid_is_refused_with_its_key() {
    let dir = scratch("citation-bad");
    let m = crate::common::manifest(
        &dir,
        "bad.yaml",
        "name: bad\nauthors:\n  - {name: X, orcid: 0000-0002-1825-0098}\ngrid:\n  k: {values: [1.2]}\n  mu: {values: [0.4]}\n",
    );
    let o = crate::common::archstudy(&["check", m.to_str().unwrap()]);
    crate::common::assert_usage_error(&o, &["bad.yaml", "authors[0].orcid", "0000-0002-1825-0098"]);
}
