//! The memory estimate of a run, from its plan. Besides the program, a run keeps a few bytes
//! of every case (its cell code and solve time); while it analyses, it holds the rows of one
//! chunk and their table; while it reports, the rows of the figure lattice it reads back; and a
//! study that locates bifurcations arch by arch holds the states and figures of every arch's
//! bifurcations. The two phases follow each other, so the larger counts. What a case holds
//! depends on its find (a state, a load factor with its mechanism, a critical value with its
//! collapse and gap), so each find has its own bytes per case, measured on release builds
//! (`/usr/bin/time -v`, maximum resident set size). A plan that does not fit is refused with
//! the shards that would fit (a shard analyses and stores, and draws nothing), or, when not
//! even one case would fit, without advice to shard.

use crate::manifest::Manifest;
use crate::scene::Find;

/// Memory every case keeps for the whole run, in bytes: its cell code for the boundaries and
/// its solve time for the report's totals. Measured: a 4001² state map peaks at 893 MB and a
/// 1001² one at 660 MB, 16 bytes a case more; 64 leaves a margin.
pub const BYTES_PER_CASE: u64 = 64;

/// Memory of a run whatever its plan, in bytes: the program with its fonts and templates,
/// the thread stacks, the Parquet writers and the figures being drawn. Measured: a 37-case
/// load-factor study peaks at 88 MB, a 4,900-case thresholds study at 44 MB.
pub const PROGRAM_BYTES: u64 = 128 << 20;

/// Cases of the chunk a run analyses and stores at a time.
pub const CHUNK_CASES: u64 = crate::store::BLOCK_ROWS as u64;

/// Memory per case of the chunk being analysed of a study of states, thrusts or thresholds,
/// in bytes: the engine's rows and their table. Measured: a 512² state map (262,144 cases)
/// peaks at 385 MB and a 512² thrust map at 434 MB, 1.3 and 1.5 kB a case over 40 MB.
pub const CHUNK_BYTES_STATE: u64 = 1536;

/// Memory per case of the chunk being analysed of a study that finds load factors, in bytes:
/// each row keeps the mechanism of its static limit and of its first complete solution.
/// Measured: 61,061 cases peak at 236 MB, 262,262 at 583 MB, and a 1001² map at 607 MB while
/// it analyses (2.4 and 1.9 kB a case over 88 MB).
pub const CHUNK_BYTES_LOAD_FACTOR: u64 = 2560;

/// Memory per case of the chunk being analysed of a study of critical thicknesses or
/// frictions, in bytes. Measured: 61,000 friction finds hold 90 MB while they are analysed
/// (1.1 kB a case).
pub const CHUNK_BYTES_CRITICAL: u64 = 1536;

/// Memory per case of the figure lattice of a study of states, thrusts or thresholds, in
/// bytes: the rows the figures and the report read back. Measured: a 1001² state map peaks
/// at 660 MB (620 bytes a case over 40 MB).
pub const LATTICE_BYTES_PER_CASE: u64 = 670;

/// Memory per case of the figure lattice of a study that finds load factors, in bytes: the
/// load factor, position and mechanism of each. Measured: a 1001² load-factor map peaks at
/// 1.08 GB while it reports (990 bytes a case over 88 MB).
pub const LATTICE_BYTES_LOAD_FACTOR: u64 = 1024;

/// Memory per case of the figure lattice of a study of critical thicknesses or frictions, in
/// bytes: each row's critical value, collapse and gap. Measured: 30,500 and 61,000 friction
/// finds over the same 244 arches peak at 327 and 384 MB, 1.9 kB a case more.
pub const LATTICE_BYTES_CRITICAL: u64 = 2048;

/// Memory per arch and load case of a study of states, thicknesses or frictions with an arch
/// axis, in bytes: the limit states at the arch's bifurcations, their mechanisms and figures.
/// Measured: thickness finds over 70 and 140 arches (4,900 and 19,600 cases) peak at 122 and
/// 176 MB; friction finds over 244 arches (168 bifurcations) at 327 MB with 30,500 cases.
pub const ARCH_BYTES: u64 = 1 << 20;

/// Memory of `archstudy verify` per case, in bytes: it re-runs the study and compares the
/// stored tables with the new ones a block of rows at a time. Measured: verify of a 1001²
/// state map peaks at 545 MB (2.14 GB when it compared whole tables).
pub const VERIFY_BYTES_PER_CASE: u64 = 256;

/// What a run of a plan holds in memory, from its manifest: see the module's description.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MemoryModel {
    /// Bytes every case keeps for the whole run.
    pub per_case: u64,
    /// Bytes per case of the chunk being analysed.
    pub chunk: u64,
    /// Bytes per case of the figure lattice.
    pub lattice: u64,
    /// Bytes of the bifurcation states and figures of every arch.
    pub arches: u64,
    /// Cases of the figure lattice, which the report reads back: at most 1001 values of each
    /// K, t/R or μ axis, every value of the other axes, for each load case
    /// ([`FigureLattice::kept`]; none for a study of uncertain parameters).
    pub lattice_cases: u64,
}

impl MemoryModel {
    /// The model of a study of states (the default find) on one arch.
    /// The model of a state map over K and μ on one arch: its figure lattice holds at most
    /// 1001² cases.
    pub const STATE: MemoryModel = MemoryModel {
        per_case: BYTES_PER_CASE,
        chunk: CHUNK_BYTES_STATE,
        lattice: LATTICE_BYTES_PER_CASE,
        arches: ARCH_BYTES,
        lattice_cases: 1001 * 1001,
    };

    /// The model of the run of `m`: the largest bytes per case of its load cases' finds, its
    /// figure lattice, and [`ARCH_BYTES`] for each group of cases in which bifurcations are
    /// located (one for each value of the arch axes, half-angle, eccentricity, joints and
    /// voussoirs, and of a point load's position) of each load case that locates them; a
    /// study of uncertain parameters locates none.
    pub fn of(m: &Manifest) -> Self {
        let groups: u64 = m
            .grid
            .iter()
            .filter(|a| a.name.splits_groups())
            .map(|a| a.values.len() as u64)
            .product();
        let kept = crate::report::reduce::FigureLattice::of(m).kept();
        let mut out = MemoryModel {
            per_case: BYTES_PER_CASE,
            chunk: 0,
            lattice: 0,
            arches: 0,
            lattice_cases: u64::try_from(kept).unwrap_or(u64::MAX),
        };
        for lc in &m.load_cases {
            let (chunk, lattice) = match lc.find {
                Find::LoadFactor => (CHUNK_BYTES_LOAD_FACTOR, LATTICE_BYTES_LOAD_FACTOR),
                Find::Thickness | Find::Friction => (CHUNK_BYTES_CRITICAL, LATTICE_BYTES_CRITICAL),
                Find::State | Find::Thrust | Find::Thresholds => {
                    (CHUNK_BYTES_STATE, LATTICE_BYTES_PER_CASE)
                }
            };
            out.chunk = out.chunk.max(chunk);
            out.lattice = out.lattice.max(lattice);
            if m.sampling.is_none()
                && matches!(lc.find, Find::State | Find::Thickness | Find::Friction)
            {
                out.arches = out.arches.saturating_add(groups.saturating_mul(ARCH_BYTES));
            }
        }
        out
    }

    /// The model of `archstudy verify` of the run of `m`: the run's, at
    /// [`VERIFY_BYTES_PER_CASE`] a case.
    pub fn verify_of(m: &Manifest) -> Self {
        MemoryModel {
            per_case: VERIFY_BYTES_PER_CASE,
            ..Self::of(m)
        }
    }

    /// The larger of the chunk being analysed and the figure lattice, in bytes.
    fn phase_bytes(&self, cases: u64) -> u64 {
        let chunk = cases.min(CHUNK_CASES).saturating_mul(self.chunk);
        let lattice = cases.min(self.lattice_cases).saturating_mul(self.lattice);
        chunk.max(lattice)
    }

    /// The memory of a run of `cases` cases besides the bytes each case keeps: the program,
    /// the larger phase and the arches.
    pub fn base_bytes(&self, cases: u64) -> u64 {
        PROGRAM_BYTES
            .saturating_add(self.phase_bytes(cases))
            .saturating_add(self.arches)
    }

    /// The memory estimate of a run of `cases` cases, in bytes.
    pub fn needed(&self, cases: u64) -> u64 {
        cases
            .saturating_mul(self.per_case)
            .saturating_add(self.base_bytes(cases))
    }

    /// The memory estimate of a shard of `cases` cases, which analyses and stores them chunk
    /// by chunk and draws nothing, in bytes.
    pub fn shard_needed(&self, cases: u64) -> u64 {
        PROGRAM_BYTES
            .saturating_add(cases.min(CHUNK_CASES).saturating_mul(self.chunk))
            .saturating_add(cases.saturating_mul(self.per_case))
    }

    /// The most cases a shard can hold in `available` bytes, or None when not even one case
    /// fits.
    fn shard_cases_that_fit(&self, available: u64) -> Option<u64> {
        if self.shard_needed(1) > available {
            return None;
        }
        let full = self.shard_needed(CHUNK_CASES);
        let fits = if full <= available {
            CHUNK_CASES + (available - full) / self.per_case.max(1)
        } else {
            (available - PROGRAM_BYTES) / self.chunk.saturating_add(self.per_case).max(1)
        };
        Some(fits.max(1))
    }

    /// Refuses a plan of `cases` cases whose run would need more memory than `available`,
    /// naming both, before anything is allocated. The shards it advises each fit in
    /// `available`; when not even one case of a shard fits, it advises more memory instead.
    pub fn check(&self, cases: u128, available: Option<u64>) -> Result<(), String> {
        let Some(available) = available else {
            return Ok(());
        };
        let cases = u64::try_from(cases).unwrap_or(u64::MAX);
        let needed = self.needed(cases);
        if needed <= available {
            return Ok(());
        }
        let head = format!(
            "the study has {cases} cases, whose run needs about {} of memory ({} bytes per case \
             and {} besides), but {} is available (the smaller of the free memory and `ulimit -v`)",
            gib(needed),
            self.per_case,
            gib(self.base_bytes(cases)),
            gib(available)
        );
        let Some(fits) = self.shard_cases_that_fit(available) else {
            return Err(format!(
                "{head}: a shard of a single case needs about {}, so no shard would fit \
                 either; raise `ulimit -v` or free memory to at least {}",
                gib(self.shard_needed(1)),
                gib(needed)
            ));
        };
        let shards = cases.div_ceil(fits);
        if shards == 1 {
            return Err(format!(
                "{head}: its analysis fits without the figures: run it as one shard, \
                 `archstudy run STUDY --shard 1/1`, which analyses and stores its {cases} cases \
                 (about {}), then `archstudy merge` it on a machine with about {} of memory to \
                 draw the figures and reports, or reduce the steps of the grid axes",
                gib(self.shard_needed(cases)),
                gib(needed)
            ));
        }
        Err(format!(
            "{head}: run it in shards of at most {fits} cases, `archstudy run STUDY --shard I/N` \
             with N ≥ {shards} (one process or cluster task per shard, then `archstudy merge` on a \
             machine with about {} of memory; `archstudy slurm STUDY --shards N` writes the job \
             array), or reduce the steps of the grid axes (or the samples of a study of \
             uncertain parameters)",
            gib(needed)
        ))
    }
}

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
pub fn gib(bytes: u64) -> String {
    format!("{:.1} GiB", bytes as f64 / f64::from(1u32 << 30))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    /// The manifest of a study of `find` under `kind` over `axes` (YAML lines of `grid:`).
    fn study(find: &str, kind: &str, axes: &str) -> Manifest {
        let text = format!(
            "name: a\narch: {{shape: circular, joints: radial, weight: annular, voussoirs: continuum}}\n\
             find: {find}\nload_cases:\n  - {{name: l, kind: {kind}}}\ngrid:\n{axes}"
        );
        crate::manifest::parse(&text, Path::new("a.yaml")).unwrap()
    }

    fn cases(m: &Manifest) -> u64 {
        u64::try_from(crate::plan::case_count(m)).unwrap()
    }

    #[test]
    fn every_measured_peak_is_covered_and_the_growth_within_two_and_a_half_times() {
        let km = |k: u32, mu: u32| {
            format!(
                "  k: {{from: 1.1, to: 1.6, steps: {k}}}\n  mu: {{from: 0.3, to: 1.0, steps: {mu}}}\n"
            )
        };
        let arches = |first: &str, n: u32, second: u32| {
            format!(
                "  {first}: {{from: 0.35, to: 0.9, steps: {second}}}\n  half_angle_deg: {{from: 60, to: 90, steps: {n}}}\n"
            )
        };
        let friction = |k: u32| {
            format!(
                "  k: {{from: 1.1, to: 1.6, steps: {k}}}\n  half_angle_deg: {{from: 60, to: 90, steps: 244}}\n"
            )
        };
        // Peak resident memory of runs of release builds (`/usr/bin/time -v`), in bytes.
        let runs = [
            (
                study("state", "self_weight", &km(512, 512)),
                385_372u64 << 10,
            ),
            // 2026-12-08: the regime map is built while the other figures are drawn.
            (study("state", "self_weight", &km(1001, 1001)), 660_000_000),
            (study("state", "self_weight", &km(4001, 4001)), 893_000_000),
            (study("thrust", "self_weight", &km(512, 512)), 434_188 << 10),
            (
                study("load_factor", "horizontal", &km(1001, 61)),
                236_000_000,
            ),
            (
                study("load_factor", "horizontal", &km(1001, 262)),
                583_000_000,
            ),
            // 2026-12-08: its λ map and load-factor figures are built side by side.
            (
                study("load_factor", "horizontal", &km(1001, 1001)),
                1_124_516 << 10,
            ),
            (
                study("friction", "self_weight", &friction(125)),
                326_860 << 10,
            ),
            // Three arches of 1001² cases each (2026-11-26, a build that read every row
            // back whole): every arch's lattice is read back.
            (
                study(
                    "state",
                    "self_weight",
                    &format!(
                        "{}  voussoirs: {{values: [8, 24, continuum]}}\n",
                        km(1001, 1001)
                    ),
                ),
                1_780_000_000,
            ),
            (
                study("friction", "self_weight", &friction(250)),
                383_856 << 10,
            ),
            (
                study("thickness", "self_weight", &arches("mu", 70, 70)),
                121_548 << 10,
            ),
            (
                study("thickness", "self_weight", &arches("mu", 140, 140)),
                176_196 << 10,
            ),
            (
                study(
                    "thresholds",
                    "self_weight",
                    "  half_angle_deg: {from: 45, to: 90, steps: 4900}\n",
                ),
                43_516 << 10,
            ),
        ];
        for (m, peak) in &runs {
            // Small runs are dominated by the program's fixed part, whose measure is the
            // smallest run's; the rest is held to the measured growth.
            let estimate = MemoryModel::of(m).needed(cases(m));
            assert!(
                estimate >= *peak && estimate - PROGRAM_BYTES <= peak * 5 / 2,
                "{} cases of {:?}: estimate {estimate}, peak {peak}",
                cases(m),
                m.load_cases[0].find
            );
        }
        // The first of four shards of the 1001² load-factor map (250,501 cases) peaks at
        // 549 MB; a shard draws nothing.
        let lf = &runs[6].0;
        let shard = MemoryModel::of(lf).shard_needed(250_501);
        assert!(
            (549_036u64 << 10..=2 * (549_036 << 10)).contains(&shard),
            "{shard}"
        );
    }

    #[test]
    fn each_find_holds_its_own_rows_and_arches_count_for_bifurcations() {
        let two = "  k: {from: 1.1, to: 1.6, steps: 3}\n  mu: {values: [0.4]}\n";
        let lf = MemoryModel::of(&study("load_factor", "horizontal", two));
        assert_eq!((lf.chunk, lf.lattice, lf.arches), (2560, 1024, 0));
        let state = MemoryModel::of(&study("state", "self_weight", two));
        assert_eq!(
            state,
            MemoryModel {
                lattice_cases: 3,
                ..MemoryModel::STATE
            }
        );
        // A 4001² map's figures are drawn from 1001 values of each axis; an arch axis and a
        // point load's position are kept whole, and each is a group of bifurcations.
        let big =
            "  k: {from: 1.1, to: 1.6, steps: 4001}\n  mu: {from: 0.3, to: 1.0, steps: 4001}\n";
        assert_eq!(
            MemoryModel::of(&study("state", "self_weight", big)).lattice_cases,
            1001 * 1001
        );
        let moving = "  k: {from: 1.1, to: 1.6, steps: 2001}\n  mu: {values: [0.4, 0.5]}\n  \
                      at_deg: {from: -40, to: 40, steps: 5}\n";
        let line = MemoryModel::of(&study("state", "point, lambda: 1", moving));
        assert_eq!((line.lattice_cases, line.arches), (1001 * 2 * 5, 5 << 20));
        let by_arch = "  mu: {values: [0.4, 0.5]}\n  half_angle_deg: {values: [60, 70, 80]}\n  \
                       voussoirs: {values: [5, 7]}\n";
        let thickness = MemoryModel::of(&study("thickness", "self_weight", by_arch));
        assert_eq!((thickness.chunk, thickness.lattice), (1536, 2048));
        assert_eq!(thickness.arches, 6 << 20);
        // 12 cases: 128 MiB, 12 × 2048 bytes of lattice, 12 × 64 and the six arches.
        assert_eq!(
            thickness.needed(12),
            (128 << 20) + 12 * 2048 + 12 * 64 + (6 << 20)
        );
    }

    #[test]
    fn a_plan_too_large_for_the_memory_is_refused_naming_shards_and_the_memory() {
        let gib4 = 4u64 << 30;
        let state = MemoryModel::STATE;
        assert!(state.check(16_008_001, Some(gib4)).is_ok());
        assert!(state.check(100_000_000, None).is_ok());
        let e = state.check(100_000_000, Some(gib4)).unwrap_err();
        // 10⁸ cases at 64 bytes, 128 MiB, 1001² × 670 bytes of lattice and one arch besides
        // need 6.72 GiB. A shard of s cases needs 128 MiB, 2¹⁸ × 1536 bytes and 64 s: 4 GiB
        // holds s = (4 GiB − 128 MiB − 2¹⁸ × 1536)/64 = 58,720,256, so 2 shards.
        for part in [
            "100000000 cases",
            "6.7 GiB",
            "64 bytes per case",
            "4.0 GiB is available",
            "shards of at most 58720256 cases",
            "--shard I/N` with N ≥ 2",
            "archstudy merge` on a machine with about 6.7 GiB",
        ] {
            assert!(e.contains(part), "{part}: {e}");
        }
    }

    #[test]
    fn a_small_plan_is_estimated_by_its_own_cases() {
        // A 37-case load-factor study: 128 MiB + 37 × (2560 + 64) bytes; it fits under
        // `ulimit -v 600000`.
        let m = study(
            "load_factor",
            "horizontal",
            "  k: {from: 1.1, to: 1.6, steps: 37}\n  mu: {values: [0.6]}\n",
        );
        let model = MemoryModel::of(&m);
        assert_eq!(model.needed(37), (128 << 20) + 37 * (2560 + 64));
        assert!(model.check(37, Some(600_000 << 10)).is_ok());
    }

    #[test]
    fn a_plan_whose_figures_alone_do_not_fit_is_advised_one_shard_and_a_larger_merge() {
        // 10⁶ cases whose lattice takes 10 kB a case: 9.5 GiB to draw, 0.6 GiB to analyse.
        let heavy = MemoryModel {
            lattice: 10_000,
            ..MemoryModel::STATE
        };
        let e = heavy.check(1_000_000, Some(2 << 30)).unwrap_err();
        for part in [
            "--shard 1/1",
            "(about 0.6 GiB)",
            "9.5 GiB of memory to draw",
        ] {
            assert!(e.contains(part), "{part}: {e}");
        }
        assert!(!e.contains("N ≥ 1"), "{e}");
    }

    #[test]
    fn no_shards_are_advised_when_not_even_one_case_fits() {
        let e = MemoryModel::STATE.check(37, Some(100 << 20)).unwrap_err();
        assert!(!e.contains("--shard"), "{e}");
        assert!(
            e.contains("no shard would fit") && e.contains("ulimit -v"),
            "{e}"
        );
    }

    #[test]
    fn every_advised_shard_fits() {
        let lf = MemoryModel {
            chunk: CHUNK_BYTES_LOAD_FACTOR,
            lattice: LATTICE_BYTES_LOAD_FACTOR,
            arches: 0,
            ..MemoryModel::STATE
        };
        for model in [MemoryModel::STATE, lf] {
            for available in [200u64 << 20, 600_000 << 10, 1 << 30, 4 << 30] {
                for cases in [10_000u64, 3_000_000, 100_000_000] {
                    let Err(e) = model.check(u128::from(cases), Some(available)) else {
                        continue;
                    };
                    let Some(fits) = model.shard_cases_that_fit(available) else {
                        assert!(!e.contains("--shard"), "{e}");
                        continue;
                    };
                    if fits >= cases {
                        assert!(e.contains("--shard 1/1"), "{e}");
                        assert!(model.shard_needed(cases) <= available, "{e}");
                        continue;
                    }
                    assert!(e.contains(&format!("at most {fits} cases")), "{e}");
                    assert!(model.shard_needed(fits) <= available, "{e}");
                    assert!(model.shard_needed(fits + 1) > available, "{e}");
                }
            }
        }
    }
}
