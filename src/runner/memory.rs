//! The memory estimate of a run, from its plan: a fixed part for the program, a part that
//! grows with the cases up to the figure lattice (at most 1001² of them are held for the
//! figures), and the bytes every case keeps. A plan that does not fit is refused with the
//! shards that would fit, or, when not even one case would, without advice to shard.

use crate::manifest::Manifest;

/// Memory of a run per case, in bytes: the case's cell code, its cell in the boundaries'
/// grid and its solve time in the report's totals (the rows themselves are stored and
/// dropped chunk by chunk). Measured (release build): a 1001² state map peaks at 583 MB and a
/// 4001² one at 790 MB, 14 bytes more a case; 64 leaves a margin.
pub const BYTES_PER_CASE: u64 = 64;

/// Memory of a run whatever its plan, in bytes: the program with its fonts and templates,
/// the thread stacks and the Parquet writers. Measured (release build): a 37-case
/// load-factor study peaks at 88 MB, a 2 × 2 state study at 61 MB.
pub const PROGRAM_BYTES: u64 = 128 << 20;

/// Cases of the figure lattice at most (1001 values of each of two axes): the rows the
/// figures and the report hold, and beyond which a run's chunk does not grow.
pub const LATTICE_CASES: u64 = 1001 * 1001;

/// Memory per case of the figure lattice and of the chunk being analysed, in bytes: the
/// engine's rows and their table, and the figure data of the lattice. Measured: a 1001²
/// state map peaks at 612 MB, a 1001² load-factor map at 1.00 GB (since the engine keeps one
/// buffer of rows for all chunks and the report builds the rows it keeps in place, one
/// block of results.parquet at a time, the state map peaks at 539 MB); 670 bytes a lattice
/// case and [`PROGRAM_BYTES`] give the 768 MiB besides the cases that both leave room in.
pub const LATTICE_BYTES_PER_CASE: u64 = 670;

/// Memory of a run per case when a load case finds a load factor, in bytes: the figure data
/// and the report keep the load factor, position and mechanism of the cases of the figure
/// lattice (every case up to 1001 values an axis, so at most 1001² of them) and a few cases
/// singled out over all. Measured (release build): a 1001² load-factor map peaks at 1.00 GB
/// (1.28 GB when every case was read whole), a 2001² one at 1.05 GB, 18 bytes a case more;
/// 256 covers the lattice of a 1001² map with a margin.
pub const LOAD_FACTOR_BYTES_PER_CASE: u64 = 256;

/// Memory of `archstudy verify` per case, in bytes: it re-runs the study and compares the
/// stored tables with the new ones a block of rows at a time, so it needs what the re-run
/// needs (at most [`LOAD_FACTOR_BYTES_PER_CASE`]). Measured: verify of a 1001² state map
/// peaks at 545 MB (2.14 GB when it compared whole tables).
pub const VERIFY_BYTES_PER_CASE: u64 = LOAD_FACTOR_BYTES_PER_CASE;

/// Returns the memory freed by a chunk's rows to the operating system. The rows of a chunk
/// (a load factor's hinges, sliding joints and work terms) are many small allocations made
/// on every worker thread; glibc keeps what they free in each thread's heap, fragmented, so
/// that without this the peak memory of a run of load factors creeps up chunk after chunk
/// (measured: 664 MB at 5·10⁵ cases, 851 MB at 10⁶, 960 MB at 2·10⁶).
pub fn release_freed_memory() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: malloc_trim only returns free pages of glibc's heaps to the kernel; it reads
    // and writes no memory of this program's.
    unsafe {
        libc::malloc_trim(0);
    }
}

/// The memory this process may use, in bytes: the smaller of the available memory
/// (/proc/meminfo MemAvailable) and the address-space limit (`ulimit -v`), when known.
pub fn available_memory() -> Option<u64> {
    let field = |text: &str, key: &str| -> Option<u64> {
        let line = text.lines().find(|l| l.starts_with(key))?;
        line[key.len()..]
            .split_whitespace()
            .next()?
            .parse::<u64>()
            .ok()
    };
    let avail = std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|t| field(&t, "MemAvailable:"))
        .map(|kb| kb.saturating_mul(1024));
    let limit = std::fs::read_to_string("/proc/self/limits")
        .ok()
        .and_then(|t| field(&t, "Max address space"));
    match (avail, limit) {
        (Some(a), Some(l)) => Some(a.min(l)),
        (a, l) => a.or(l),
    }
}

/// Bytes as GiB to one decimal, e.g. `0.8 GiB`.
pub(super) fn gib(bytes: u64) -> String {
    format!("{:.1} GiB", bytes as f64 / f64::from(1u32 << 30))
}

/// The memory of a run of `cases` cases besides the bytes each case keeps: [`PROGRAM_BYTES`]
/// and [`LATTICE_BYTES_PER_CASE`] for each case up to [`LATTICE_CASES`].
pub fn base_bytes(cases: u64) -> u64 {
    PROGRAM_BYTES.saturating_add(
        cases
            .min(LATTICE_CASES)
            .saturating_mul(LATTICE_BYTES_PER_CASE),
    )
}

/// The memory estimate of a run of `cases` cases at `per_case` bytes a case.
pub fn needed_bytes_at(cases: u64, per_case: u64) -> u64 {
    cases
        .saturating_mul(per_case)
        .saturating_add(base_bytes(cases))
}

/// The memory estimate of a run of `cases` cases, in bytes.
pub fn needed_bytes(cases: u64) -> u64 {
    needed_bytes_at(cases, BYTES_PER_CASE)
}

/// The memory per case of a manifest's run ([`BYTES_PER_CASE`], or
/// [`LOAD_FACTOR_BYTES_PER_CASE`] for a study that finds load factors).
pub fn bytes_per_case(m: &Manifest) -> u64 {
    if m.load_cases
        .iter()
        .any(|l| l.find == crate::scene::Find::LoadFactor)
    {
        LOAD_FACTOR_BYTES_PER_CASE
    } else {
        BYTES_PER_CASE
    }
}

/// Refuses a plan of `cases` cases whose run would need more memory than `available`
/// (see [`BYTES_PER_CASE`]), naming both, before anything is allocated.
pub fn check_memory(cases: u128, available: Option<u64>) -> Result<(), String> {
    check_memory_at(cases, BYTES_PER_CASE, available)
}

/// The most cases a run at `per_case` bytes a case can hold in `available` bytes, or None
/// when not even one case fits.
fn cases_that_fit(per_case: u64, available: u64) -> Option<u64> {
    let room = available.checked_sub(PROGRAM_BYTES)?;
    let in_lattice = per_case.saturating_add(LATTICE_BYTES_PER_CASE).max(1);
    let fits = if room / in_lattice <= LATTICE_CASES {
        room / in_lattice
    } else {
        LATTICE_CASES + (room - LATTICE_CASES * in_lattice) / per_case.max(1)
    };
    (fits >= 1).then_some(fits)
}

/// [`check_memory`] at `per_case` bytes a case. The shards it advises each fit in
/// `available`; when not even one case fits, it advises more memory instead.
pub fn check_memory_at(cases: u128, per_case: u64, available: Option<u64>) -> Result<(), String> {
    let Some(available) = available else {
        return Ok(());
    };
    let cases = u64::try_from(cases).unwrap_or(u64::MAX);
    let needed = needed_bytes_at(cases, per_case);
    if needed <= available {
        return Ok(());
    }
    let head = format!(
        "the study has {cases} cases, whose run needs about {} of memory ({} bytes per case and {} \
         besides), but {} is available (the smaller of the free memory and `ulimit -v`)",
        gib(needed),
        per_case,
        gib(base_bytes(cases)),
        gib(available)
    );
    let Some(fits) = cases_that_fit(per_case, available) else {
        return Err(format!(
            "{head}: the program alone needs about {}, so no shard would fit either; raise \
             `ulimit -v` or free memory to at least {}",
            gib(PROGRAM_BYTES),
            gib(needed)
        ));
    };
    let shards = cases.div_ceil(fits);
    Err(format!(
        "{head}: run it in shards of at most {fits} cases, `archstudy run STUDY --shard I/N` \
         with N ≥ {shards} (one process or cluster task per shard, then `archstudy merge` on a \
         machine with that memory; `archstudy slurm STUDY --shards N` writes the job array), \
         or reduce the steps of the grid axes (or the samples of a study of uncertain \
         parameters)"
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    #[test]
    fn a_plan_too_large_for_the_memory_is_refused_naming_shards_and_the_memory() {
        let gib4 = 4u64 << 30;
        assert!(check_memory(16_008_001, Some(gib4)).is_ok());
        assert!(check_memory(100_000_000, None).is_ok());
        let e = check_memory(100_000_000, Some(gib4)).unwrap_err();
        // 10⁸ cases at 64 bytes, 128 MiB and 670 bytes a lattice case besides need 6.71 GiB;
        // 4 GiB holds (4 GiB − 128 MiB − 1001² × 670)/64 + 1001² = 54,522,014 cases, so 2
        // shards.
        for part in [
            "100000000 cases",
            "6.7 GiB",
            "64 bytes per case",
            "4.0 GiB is available",
            "shards of at most 54522014 cases",
            "--shard I/N` with N ≥ 2",
            "archstudy merge",
        ] {
            assert!(e.contains(part), "{part}: {e}");
        }
    }

    #[test]
    fn a_small_plan_is_estimated_by_its_own_cases() {
        // A 37-case load-factor study: 128 MiB + 37 × (670 + 256) bytes, far below the
        // 768 MiB of a 1001² map's lattice; it fits under `ulimit -v 600000`.
        let needed = needed_bytes_at(37, LOAD_FACTOR_BYTES_PER_CASE);
        assert_eq!(needed, (128 << 20) + 37 * 926);
        assert!(check_memory_at(37, LOAD_FACTOR_BYTES_PER_CASE, Some(600_000 << 10)).is_ok());
    }

    #[test]
    fn no_shards_are_advised_when_not_even_one_case_fits() {
        let e = check_memory_at(37, LOAD_FACTOR_BYTES_PER_CASE, Some(100 << 20)).unwrap_err();
        assert!(!e.contains("--shard"), "{e}");
        assert!(
            e.contains("no shard would fit") && e.contains("ulimit -v"),
            "{e}"
        );
    }

    #[test]
    fn every_advised_shard_fits() {
        for available in [200u64 << 20, 600_000 << 10, 1 << 30, 4 << 30] {
            for cases in [10_000u64, 3_000_000, 100_000_000] {
                let Err(e) = check_memory_at(u128::from(cases), 64, Some(available)) else {
                    continue;
                };
                let fits = cases_that_fit(64, available).expect(&e);
                assert!(needed_bytes_at(fits, 64) <= available, "{e}");
                assert!(needed_bytes_at(fits + 1, 64) > available, "{e}");
            }
        }
    }

    #[test]
    fn a_load_factor_map_is_estimated_at_its_own_cost_per_case() {
        let gib4 = 4u64 << 30;
        let m = |find: &str, kind: &str| {
            crate::manifest::parse(
                &format!("name: a\nfind: {find}\nload_cases:\n  - {{name: h, kind: {kind}}}\ngrid:\n  k: {{from: 1.1, to: 1.6, steps: 3}}\n  mu: {{values: [0.4]}}\n"),
                Path::new("a.yaml"),
            )
            .unwrap()
        };
        assert_eq!(
            bytes_per_case(&m("load_factor", "horizontal")),
            LOAD_FACTOR_BYTES_PER_CASE
        );
        assert_eq!(bytes_per_case(&m("state", "self_weight")), BYTES_PER_CASE);
        // 1.5 × 10⁷ load factors at 256 bytes need 4.3 GiB: refused at 4 GiB, in 2 shards of
        // at most (4 GiB − 128 MiB − 1001² × 670)/256 + 1001² = 13,630,503 cases; the same
        // count of states fits.
        let e = check_memory_at(15_000_000, LOAD_FACTOR_BYTES_PER_CASE, Some(gib4)).unwrap_err();
        assert!(
            e.contains("256 bytes per case") && e.contains("at most 13630503 cases"),
            "{e}"
        );
        assert!(e.contains("4.3 GiB") && e.contains("N ≥ 2"), "{e}");
        assert!(check_memory_at(15_000_000, BYTES_PER_CASE, Some(gib4)).is_ok());
    }
}
