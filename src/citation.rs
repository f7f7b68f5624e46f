//! How to cite a run: `ro-crate-metadata.json` in every run directory (and so in every
//! archive), an RO-Crate 1.1 description of the study (title, description, authors and
//! licence from the manifest), of the software that ran it (version, commit, licence), of
//! the run (start and end) and of every file it wrote.

use crate::manifest::{Author, Manifest};
use crate::output::{CRATE_METADATA, RunLayout, write_atomic};
use crate::provenance::RunInfo;
use anyhow::Result;
use serde_json::{Value, json};

/// The licence archstudy itself is distributed under.
pub const SOFTWARE_LICENSE: &str = env!("CARGO_PKG_LICENSE");

/// The media type of a file of a run, from its extension.
fn media_type(rel: &str) -> &'static str {
    match rel.rsplit('.').next().unwrap_or("") {
        "parquet" => "application/vnd.apache.parquet",
        "json" => "application/json",
        "yaml" | "yml" => "application/yaml",
        "html" => "text/html",
        "md" => "text/markdown",
        "svg" => "image/svg+xml",
        "png" => "image/png",
        "pdf" => "application/pdf",
        "csv" => "text/csv",
        "tex" => "application/x-tex",
        _ => "application/octet-stream",
    }
}

fn author_entity(i: usize, a: &Author) -> Value {
    let id = a.orcid.as_ref().map_or_else(
        || format!("#author-{}", i + 1),
        |o| format!("https://orcid.org/{o}"),
    );
    let mut e = json!({"@id": id, "@type": "Person", "name": a.name});
    if let Some(aff) = &a.affiliation {
        e["affiliation"] = json!(aff);
    }
    e
}

/// The RO-Crate metadata of a run, one entity per `@id` (authors with one ORCID are one
/// person, named as first listed): `files` are the run directory's files (relative path,
/// size in bytes), as [`RunLayout::files`] lists them.
pub fn crate_metadata(manifest: &Manifest, info: &RunInfo, files: &[(String, u64)]) -> Value {
    // One entity per identifier: an author listed twice under one ORCID is one person.
    let mut authors: Vec<Value> = Vec::new();
    for (i, a) in manifest.authors.iter().enumerate() {
        let e = author_entity(i, a);
        if !authors.iter().any(|x| x["@id"] == e["@id"]) {
            authors.push(e);
        }
    }
    let file_entities: Vec<Value> = files
        .iter()
        .map(|(rel, size)| {
            json!({"@id": rel, "@type": "File", "encodingFormat": media_type(rel),
                   "contentSize": size.to_string()})
        })
        .collect();
    let parts: Vec<Value> = files.iter().map(|(rel, _)| json!({"@id": rel})).collect();
    let mut dataset = json!({
        "@id": "./",
        "@type": "Dataset",
        "name": manifest.title.clone().unwrap_or_else(|| manifest.name.clone()),
        "identifier": format!("{}-{}", manifest.name, info.manifest_sha256),
        "datePublished": info.finished_at,
        "hasPart": parts,
        "mainEntity": {"@id": "report.html"},
    });
    if let Some(d) = &manifest.description {
        dataset["description"] = json!(d);
    }
    if !authors.is_empty() {
        dataset["author"] =
            Value::Array(authors.iter().map(|a| json!({"@id": a["@id"]})).collect());
    }
    if let Some(l) = &manifest.license {
        dataset["license"] = json!(l);
    }
    let software = json!({
        "@id": "#archstudy",
        "@type": "SoftwareApplication",
        "name": "archstudy",
        "version": info.archstudy_version,
        "identifier": info.git_commit.clone().unwrap_or_default(),
        "license": SOFTWARE_LICENSE,
    });
    let action = json!({
        "@id": "#run",
        "@type": "CreateAction",
        "name": format!("archstudy run of {}", manifest.name),
        "instrument": {"@id": "#archstudy"},
        "object": {"@id": "manifest.yaml"},
        "result": files.iter().filter(|(r, _)| r != "manifest.yaml").map(|(r, _)| json!({"@id": r})).collect::<Vec<_>>(),
        "startTime": info.started_at,
        "endTime": info.finished_at,
    });
    let descriptor = json!({
        "@id": CRATE_METADATA,
        "@type": "CreativeWork",
        "conformsTo": {"@id": "https://w3id.org/ro/crate/1.1"},
        "about": {"@id": "./"},
    });
    let mut graph = vec![descriptor, dataset, software, action];
    graph.extend(authors);
    graph.extend(file_entities);
    json!({"@context": "https://w3id.org/ro/crate/1.1/context", "@graph": graph})
}

/// Writes the run directory's `ro-crate-metadata.json` (after every other file of the run).
pub fn write_crate_metadata(layout: &RunLayout, manifest: &Manifest, info: &RunInfo) -> Result<()> {
    let files = layout.files()?;
    let value = crate_metadata(manifest, info, &files);
    write_atomic(
        &layout.crate_metadata(),
        (serde_json::to_string_pretty(&value)? + "\n").as_bytes(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_crate_names_authors_files_and_software() {
        let m = crate::manifest::parse(
            "name: cite\ntitle: A study\nauthors:\n  - {name: Ada Lovelace, orcid: 0000-0002-1825-0097}\n  - {name: B. Author}\nlicense: CC-BY-4.0\ngrid:\n  k: {values: [1.2]}\n  mu: {values: [0.4]}\n",
            std::path::Path::new("cite.yaml"),
        )
        .unwrap();
        let info: RunInfo = serde_json::from_value(json!({
            "name": "cite", "manifest": {}, "manifest_sha256": "ab12", "manifest_path": "cite.yaml",
            "archstudy_version": "0.1.0", "git_commit": "abc", "rustc_version": "rustc",
            "command_line": [], "threads": 1, "started_at": "2026-01-01T00:00:00Z",
            "finished_at": "2026-01-01T00:00:01Z", "cases": {"total": 1, "ok": 1, "error": 0},
            "separable": true, "stages": {"plan_ms": 0.0, "engine_ms": 0.0, "store_ms": 0.0,
            "boundaries_ms": 0.0, "plots_ms": 0.0, "report_ms": 0.0},
            "boundary_refinement_analyses": 0
        }))
        .unwrap();
        let files = vec![
            ("manifest.yaml".to_string(), 10),
            ("results.parquet".to_string(), 2000),
        ];
        let c = crate_metadata(&m, &info, &files);
        let graph = c["@graph"].as_array().unwrap();
        let by_id = |id: &str| graph.iter().find(|e| e["@id"] == id).unwrap().clone();
        let dataset = by_id("./");
        assert_eq!(dataset["name"], "A study");
        assert_eq!(dataset["license"], "CC-BY-4.0");
        assert_eq!(
            dataset["author"][0]["@id"],
            "https://orcid.org/0000-0002-1825-0097"
        );
        assert_eq!(dataset["author"][1]["@id"], "#author-2");
        assert_eq!(by_id("#author-2")["name"], "B. Author");
        assert_eq!(
            by_id("results.parquet")["encodingFormat"],
            "application/vnd.apache.parquet"
        );
        assert_eq!(by_id("results.parquet")["contentSize"], "2000");
        assert_eq!(by_id("#archstudy")["identifier"], "abc");
        assert_eq!(by_id("#archstudy")["license"], SOFTWARE_LICENSE);
        assert_eq!(by_id(CRATE_METADATA)["about"]["@id"], "./");
    }

    #[test]
    fn two_authors_with_one_orcid_are_one_entity() {
        let m = crate::manifest::parse(
            "name: cite\nauthors:\n  - {name: Ada Lovelace, orcid: 0000-0002-1825-0097}\n  - {name: A. Lovelace, orcid: 0000-0002-1825-0097}\n  - {name: C}\ngrid:\n  k: {values: [1.2]}\n  mu: {values: [0.4]}\n",
            std::path::Path::new("cite.yaml"),
        )
        .unwrap();
        let info: RunInfo = serde_json::from_value(json!({
            "name": "cite", "manifest": {}, "manifest_sha256": "ab12", "manifest_path": "cite.yaml",
            "archstudy_version": "0.1.0", "git_commit": null, "rustc_version": "rustc",
            "command_line": [], "threads": 1, "started_at": "", "finished_at": "",
            "cases": {"total": 1, "ok": 1, "error": 0}, "separable": true,
            "stages": {"plan_ms": 0.0, "engine_ms": 0.0, "store_ms": 0.0,
            "boundaries_ms": 0.0, "plots_ms": 0.0, "report_ms": 0.0},
            "boundary_refinement_analyses": 0
        }))
        .unwrap();
        let c = crate_metadata(&m, &info, &[("manifest.yaml".to_string(), 10)]);
        let graph = c["@graph"].as_array().unwrap();
        let mut ids: Vec<&str> = graph.iter().map(|e| e["@id"].as_str().unwrap()).collect();
        let n = ids.len();
        ids.sort_unstable();
        ids.dedup();
        assert_eq!(ids.len(), n, "{graph:?}");
        let authors = c["@graph"][1]["author"].as_array().unwrap();
        assert_eq!(authors.len(), 2, "{authors:?}");
        let ada = graph
            .iter()
            .find(|e| e["@id"] == "https://orcid.org/0000-0002-1825-0097")
            .unwrap();
        assert_eq!(ada["name"], "Ada Lovelace");
    }
}
