//! `archstudy merge` and `archstudy slurm`: sharded runs on a cluster.

use super::args::{MergeArgs, SlurmArgs};
use super::{print_out, report_run, shown};
use crate::error::UsageError;
use crate::{merge as merging, slurm as batch};
use anyhow::Result;
use std::process::ExitCode;

/// `archstudy merge SHARD_DIR... [--out DIR]`.
pub(super) fn merge(args: &MergeArgs) -> Result<ExitCode> {
    if let Some(0) = args.jobs {
        return Err(
            UsageError::new("--jobs", 0, "the number of threads must be at least 1").into(),
        );
    }
    let Some(recheck) = merging::Recheck::parse(&args.recheck) else {
        return Err(UsageError::new(
            "--recheck",
            &args.recheck,
            "give the number of rows of each shard to analyse again (0 or more), or `all`",
        )
        .into());
    };
    let mut shards = args.shards.clone();
    if let Some(from) = &args.shards_from {
        shards.extend(merging::shards_from(from)?);
    }
    let opts = merging::MergeOptions {
        shards,
        out: args.out.clone(),
        jobs: args.jobs,
        progress: shown(args.quiet),
        command_line: std::env::args().collect(),
        recheck,
    };
    let summary = merging::merge(&opts)?;
    report_run(&summary);
    Ok(ExitCode::SUCCESS)
}

/// `archstudy slurm STUDY --shards N [...] [--submit]`.
pub(super) fn slurm(args: &SlurmArgs) -> Result<ExitCode> {
    let opts = batch::SlurmOptions {
        study: args.study.clone(),
        shards: args.shards,
        partition: args.partition.clone(),
        time: args.time.clone(),
        mem: args.mem.clone(),
        out: args.out.clone(),
        binary: std::env::current_exe()?,
    };
    let scripts = batch::write_scripts(&opts)?;
    eprintln!(
        "wrote {} ({} array tasks) and {}; the merged run will be {}",
        scripts.array.display(),
        args.shards,
        scripts.merge.display(),
        scripts.run_dir.display()
    );
    if args.submit {
        let (array, merge) = batch::submit(&scripts)?;
        print_out(&format!("array job {array}\nmerge job {merge}\n"))?;
    } else {
        eprintln!("submit both with:");
        print_out(&scripts.commands)?;
    }
    Ok(ExitCode::SUCCESS)
}
