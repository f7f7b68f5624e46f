//! `archstudy slurm STUDY --shards N`: two Slurm batch scripts for a sharded run, written to
//! `OUT/<name>.slurm/`: `array.sh`, a job array of N tasks where task T (0-based, as Slurm
//! numbers them) runs `archstudy run STUDY --shard $((T+1))/N`, and `merge.sh`, which merges
//! the N shard directories into `OUT/<name>/`. The merge job is submitted with
//! `--dependency=afterok:<array job>`, so it starts only when every task succeeded.
//! Submitting is left to the user (the commands are returned) unless asked.

use crate::error::UsageError;
use crate::runner;
use crate::shard::MAX_SHARDS;
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};

/// Options of `archstudy slurm`, as domain values.
#[derive(Debug, Clone)]
pub struct SlurmOptions {
    /// The study manifest.
    pub study: PathBuf,
    /// Number of shards (array tasks).
    pub shards: u64,
    /// `--partition` of both jobs, when given.
    pub partition: Option<String>,
    /// `--time` of each job (Slurm's `[D-]HH:MM:SS` or minutes), when given.
    pub time: Option<String>,
    /// `--mem` of each array task; default: the run's memory estimate for one chunk of a
    /// shard (a shard's memory does not grow with its size).
    pub mem: Option<String>,
    /// Directory of the shard directories, the merged run and the scripts.
    pub out: PathBuf,
    /// The archstudy binary the jobs run.
    pub binary: PathBuf,
}

/// The scripts written, and how to submit them.
#[derive(Debug, Clone)]
pub struct SlurmScripts {
    /// The job array script.
    pub array: PathBuf,
    /// The merge job script.
    pub merge: PathBuf,
    /// The shell commands that submit both, the merge after the array (`afterok`).
    pub commands: String,
    /// The directory the merged run will be.
    pub run_dir: PathBuf,
}

/// Quotes a word for a POSIX shell.
fn quote(s: &str) -> String {
    format!("'{}'", s.replace('\'', "'\\''"))
}

fn quote_path(p: &Path) -> String {
    quote(&p.display().to_string())
}

/// Refuses a path that cannot be written into a script safely: one that is not UTF-8, or
/// holds a control character (a newline would end a comment or a `#SBATCH` line), a double
/// quote or a backslash (Slurm reads neither literally in `#SBATCH --output`).
fn check_path(option: &'static str, p: &Path) -> Result<String, UsageError> {
    let refuse = || {
        UsageError::new(
            option,
            p.display().to_string().escape_debug(),
            "a UTF-8 path without control characters (newline, tab, …), `\"` or `\\`, which \
             cannot be written into a Slurm script safely",
        )
    };
    let text = p.to_str().ok_or_else(refuse)?;
    if text
        .chars()
        .any(|c| c.is_control() || c == '"' || c == '\\')
    {
        return Err(refuse());
    }
    Ok(text.to_string())
}

/// A `#SBATCH --output` file pattern for a directory and a file name that may hold Slurm's
/// replacements (`%a`): double-quoted (a space does not end it), a `%` of the directory
/// written `%%` (Slurm would expand it). The directory is checked by [`check_path`].
fn output_pattern(dir: &str, file: &str) -> String {
    format!("\"{}/{file}\"", dir.replace('%', "%%"))
}

/// Refuses a Slurm option value that could not be written into a `#SBATCH` line as is.
fn check_value(option: &'static str, v: &Option<String>, allowed: &str) -> Result<(), UsageError> {
    match v {
        Some(v)
            if v.is_empty()
                || !v
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || ":-_.,".contains(c)) =>
        {
            Err(UsageError::new(option, v, allowed))
        }
        _ => Ok(()),
    }
}

/// The share of the run's memory estimate below which `--mem` is refused: a task given less
/// than half of what the run is estimated to need is killed by Slurm, after its time in the
/// queue.
pub const MIN_MEM_FRACTION: f64 = 0.5;

/// A Slurm `--mem` value in bytes: a whole number with an optional unit K, M, G or T
/// (Slurm's default unit is M); None when it is not one.
fn slurm_mem_bytes(v: &str) -> Option<u64> {
    let (digits, unit) = match v.char_indices().find(|(_, c)| !c.is_ascii_digit()) {
        Some((i, _)) => v.split_at(i),
        None => (v, "M"),
    };
    let n: u64 = digits.parse().ok()?;
    let shift = match unit.to_ascii_uppercase().as_str() {
        "K" | "KB" => 10,
        "M" | "MB" => 20,
        "G" | "GB" => 30,
        "T" | "TB" => 40,
        _ => return None,
    };
    n.checked_mul(1u64 << shift)
}

/// Refuses a `--mem` that is not a Slurm memory size, or is far below the memory a shard
/// task is estimated to need ([`MIN_MEM_FRACTION`]).
fn check_mem(mem: &str, needed: u64) -> Result<(), UsageError> {
    let Some(bytes) = slurm_mem_bytes(mem) else {
        return Err(UsageError::new(
            "--mem",
            mem,
            "a Slurm memory size such as 4G or 800M",
        ));
    };
    if (bytes as f64) < needed as f64 * MIN_MEM_FRACTION {
        return Err(UsageError::new(
            "--mem",
            mem,
            format!(
                "at least half of the memory a shard task is estimated to need, {} (about {} \
                 MiB): a task with less is killed for want of memory; give more, or more shards",
                mem_for_bytes(needed),
                needed.div_ceil(1 << 20)
            ),
        ));
    }
    Ok(())
}

fn mem_for_bytes(bytes: u64) -> String {
    format!("{}M", bytes.div_ceil(1 << 20))
}

/// The memory estimate of a shard of `cases` cases of a study of `model`, as a Slurm `--mem`
/// value in megabytes.
fn mem_for(model: &runner::MemoryModel, cases: u64) -> String {
    mem_for_bytes(model.shard_needed(cases))
}

/// The memory estimate of the merge of a study's `cases` cases, which draws its figures and
/// reports, as a Slurm `--mem` value in megabytes.
fn merge_mem_for(model: &runner::MemoryModel, cases: u64) -> String {
    mem_for_bytes(model.needed(cases))
}

fn absolute(p: &Path) -> Result<PathBuf> {
    std::path::absolute(p).with_context(|| format!("cannot resolve {}", p.display()))
}

/// The `#SBATCH` lines shared by both jobs.
fn common_lines(o: &SlurmOptions, mem: &str) -> String {
    let mut s = String::new();
    if let Some(p) = &o.partition {
        s.push_str(&format!("#SBATCH --partition={p}\n"));
    }
    if let Some(t) = &o.time {
        s.push_str(&format!("#SBATCH --time={t}\n"));
    }
    s.push_str(&format!("#SBATCH --mem={mem}\n"));
    s
}

/// Writes `OUT/<name>.slurm/array.sh` and `merge.sh` for a study split into `shards` shards.
pub fn write_scripts(o: &SlurmOptions) -> Result<SlurmScripts> {
    if o.shards == 0 || o.shards > MAX_SHARDS {
        return Err(UsageError::new(
            "--shards",
            o.shards,
            format!("the number of shards N must be a whole number in [1, {MAX_SHARDS}]"),
        )
        .into());
    }
    check_value(
        "--partition",
        &o.partition,
        "a Slurm partition name (letters, digits, - _ .)",
    )?;
    check_value(
        "--time",
        &o.time,
        "a Slurm time limit such as 30, 02:00:00 or 1-12:00:00",
    )?;
    check_value("--mem", &o.mem, "a Slurm memory size such as 4G or 800M")?;
    check_path("STUDY", &o.study)?;
    check_path("--out", &o.out)?;
    let (m, _) = runner::load_manifest(&o.study)?;
    let total = u64::try_from(crate::plan::case_count(&m)).unwrap_or(u64::MAX);
    let largest = crate::plan::shard_ids(total, 1, o.shards);
    let task_cases = largest.end - largest.start + 1;
    let model = runner::MemoryModel::of(&m);
    if let Some(mem) = &o.mem {
        check_mem(mem, model.shard_needed(task_cases))?;
    }
    let shard_mem = o.mem.clone().unwrap_or_else(|| mem_for(&model, task_cases));
    let (study, out, binary) = (absolute(&o.study)?, absolute(&o.out)?, absolute(&o.binary)?);
    check_path("--out", &out)?;
    check_path("STUDY", &study)?;
    check_path("the archstudy binary", &binary)?;
    let dir = out.join(format!("{}.slurm", m.name));
    let logs = check_path("--out", &dir.join("logs"))?;
    std::fs::create_dir_all(dir.join("logs"))
        .with_context(|| format!("cannot create {}", dir.display()))?;
    let n = o.shards;
    let array = format!(
        "#!/bin/bash\n\
         # Shard $((SLURM_ARRAY_TASK_ID+1)) of {n} of the study {name}: tasks are numbered from 0\n\
         # by Slurm, shards from 1 by archstudy.\n\
         #SBATCH --job-name={name}-shards\n\
         #SBATCH --array=0-{last}\n\
         #SBATCH --output={output}\n\
         {common}\
         set -euo pipefail\n\
         exec {bin} run {study} --shard \"$((SLURM_ARRAY_TASK_ID + 1))/{n}\" --out {out} --quiet\n",
        name = m.name,
        last = n - 1,
        output = output_pattern(&logs, "shard-%a.out"),
        common = common_lines(o, &shard_mem),
        bin = quote_path(&binary),
        study = quote_path(&study),
        out = quote_path(&out),
    );
    // The shard directories are listed by the shell's own printf (no argument list to
    // exceed, whatever their number) and read by `merge --shards-from`.
    let list = dir.join("shards.list");
    let merge = format!(
        "#!/bin/bash\n\
         # Merges the {n} shards of the study {name} into {run}; submitted with\n\
         # --dependency=afterok on the array, so it runs only when every shard succeeded.\n\
         #SBATCH --job-name={name}-merge\n\
         #SBATCH --output={output}\n\
         {common}\
         set -euo pipefail\n\
         shopt -s nullglob\n\
         cd {out}\n\
         printf '%s\\n' ./{name}.shard-*-of-{n} > {list}\n\
         exec {bin} merge --shards-from {list} --out {out} --quiet\n",
        name = m.name,
        run = out.join(&m.name).display(),
        output = output_pattern(&logs, "merge.out"),
        common = common_lines(o, &merge_mem_for(&model, total)),
        bin = quote_path(&binary),
        out = quote_path(&out),
        list = quote_path(&list),
    );
    let (array_path, merge_path) = (dir.join("array.sh"), dir.join("merge.sh"));
    crate::output::write_atomic(&array_path, array.as_bytes())?;
    crate::output::write_atomic(&merge_path, merge.as_bytes())?;
    let commands = format!(
        "array=$(sbatch --parsable {})\nsbatch --dependency=afterok:${{array%%;*}} {}\n",
        quote_path(&array_path),
        quote_path(&merge_path)
    );
    Ok(SlurmScripts {
        array: array_path,
        merge: merge_path,
        commands,
        run_dir: out.join(&m.name),
    })
}

/// Runs `sbatch --parsable` with `args` and returns the job id it prints.
fn sbatch(args: &[&str]) -> Result<String> {
    let o = std::process::Command::new("sbatch")
        .arg("--parsable")
        .args(args)
        .output()
        .context("cannot run sbatch (is Slurm's client installed and on PATH?)")?;
    if !o.status.success() {
        anyhow::bail!(
            "sbatch {} failed: {}",
            args.join(" "),
            String::from_utf8_lossy(&o.stderr).trim()
        );
    }
    let out = String::from_utf8_lossy(&o.stdout);
    // `--parsable` prints `id` or `id;cluster`.
    let id = out.trim().split(';').next().unwrap_or("").to_string();
    if id.is_empty() || !id.chars().all(|c| c.is_ascii_digit()) {
        anyhow::bail!("sbatch printed `{}`, not a job id", out.trim());
    }
    Ok(id)
}

/// Submits the scripts: the array, then the merge depending on it (`afterok`). Returns the
/// two job ids.
/// When the merge cannot be submitted, the error names the array job already queued, how to
/// submit the merge by hand and how to cancel the array.
pub fn submit(s: &SlurmScripts) -> Result<(String, String)> {
    let array = sbatch(&[&s.array.display().to_string()])?;
    let merge = sbatch(&[
        &format!("--dependency=afterok:{array}"),
        &s.merge.display().to_string(),
    ])
    .with_context(|| {
        format!(
            "the array job {array} is queued, but its merge job could not be submitted: \
             submit it with `sbatch --dependency=afterok:{array} {}`, or cancel the array \
             with `scancel {array}`",
            quote(&s.merge.display().to_string())
        )
    })?;
    Ok((array, merge))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_mem_far_below_the_estimate_is_refused() {
        assert_eq!(slurm_mem_bytes("4G"), Some(4 << 30));
        assert_eq!(slurm_mem_bytes("800"), Some(800 << 20));
        assert_eq!(slurm_mem_bytes("1x"), None);
        let needed = 800u64 << 20;
        assert!(check_mem("1G", needed).is_ok());
        assert!(check_mem("400M", needed).is_ok());
        let e = check_mem("1M", needed).unwrap_err().to_string();
        assert!(e.contains("--mem") && e.contains("800M"), "{e}");
        assert!(check_mem("lots", needed).is_err());
    }

    #[test]
    fn quoted_words_survive_the_shell() {
        assert_eq!(quote("a b"), "'a b'");
        assert_eq!(quote("it's"), "'it'\\''s'");
    }

    #[test]
    fn the_memory_of_a_task_follows_its_find() {
        let state = runner::MemoryModel::STATE;
        assert_eq!(mem_for(&state, 0), "128M");
        // A shard of 10⁶ states: 128 MiB, a chunk of 2¹⁸ rows at 1536 bytes and 64 bytes a
        // case; its merge draws the figure lattice, 670 bytes a case, and one arch (1 MiB).
        assert_eq!(
            mem_for(&state, 1_000_000),
            format!(
                "{}M",
                ((128u64 << 20) + 262_144 * 1536 + 64_000_000).div_ceil(1 << 20)
            )
        );
        assert_eq!(
            merge_mem_for(&state, 1_000_000),
            format!(
                "{}M",
                ((128u64 << 20) + 670_000_000 + 64_000_000 + (1 << 20)).div_ceil(1 << 20)
            )
        );
    }
}
