//! The separable path of a symmetric self-weight `state` grid of circular arches with radial
//! joints: each distinct rotational domain (geometry and K) and sliding domain (geometry and
//! μ) solved once, then a comparison per case into its compact row ([`StateCase`]).

use super::{StateCase, panic_message};
use crate::analysis::circular::SymmetricCircular;
use crate::analysis::symmetric::{self, RotationalDomain, SlidingDomain};
use crate::model::Discretisation;
use crate::plan::Case;
use crate::progress::Progress;
use crate::scene::{Find, Inputs, Scene, StateAnswer};
use rayon::prelude::*;
use rustc_hash::FxHashMap;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::time::Instant;

/// Key of the geometry shared by the cases whose domains can be reused.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
struct GeomKey {
    /// α in degrees as given.
    half_angle_deg_bits: u64,
    joints: Discretisation,
    k_bits: u64,
}

/// The distinct rotational problems (geometry and K) and sliding problems (geometry and μ)
/// of a separable grid, and for each case the index of its two problems.
struct SeparableKeys {
    rot: Vec<GeomKey>,
    sld: Vec<(GeomKey, u64)>,
    cases: Vec<(usize, usize)>,
}

impl SeparableKeys {
    fn of<'a>(scenes: impl Iterator<Item = &'a Scene>) -> Self {
        let mut rot: Vec<GeomKey> = Vec::new();
        let mut rot_index: FxHashMap<GeomKey, usize> = FxHashMap::default();
        let mut sld: Vec<(GeomKey, u64)> = Vec::new();
        let mut sld_index: FxHashMap<(GeomKey, u64), usize> = FxHashMap::default();
        let mut keyed = Vec::with_capacity(scenes.size_hint().0);
        for scene in scenes {
            let a = &scene.arch;
            let rk = GeomKey {
                half_angle_deg_bits: a.half_angle_deg().to_bits(),
                joints: a.joints,
                k_bits: a.k.to_bits(),
            };
            let sk = (GeomKey { k_bits: 0, ..rk }, scene.friction.mu().to_bits());
            let ri = *rot_index.entry(rk).or_insert_with(|| {
                rot.push(rk);
                rot.len() - 1
            });
            let si = *sld_index.entry(sk).or_insert_with(|| {
                sld.push(sk);
                sld.len() - 1
            });
            keyed.push((ri, si));
        }
        SeparableKeys {
            rot,
            sld,
            cases: keyed,
        }
    }

    /// How many cases share each rotational and each sliding domain, to split its cost.
    fn uses(&self) -> (Vec<usize>, Vec<usize>) {
        let mut rot_uses = vec![0usize; self.rot.len()];
        let mut sld_uses = vec![0usize; self.sld.len()];
        for &(r, s) in &self.cases {
            rot_uses[r] += 1;
            sld_uses[s] += 1;
        }
        (rot_uses, sld_uses)
    }
}

/// A domain solved once for the cases that share it, with its solve time in µs, or the
/// message of the panic that stopped it.
type Timed<D> = Result<(D, f64), String>;

fn timed<D>(solve: impl FnOnce() -> D) -> Timed<D> {
    let t = Instant::now();
    catch_unwind(AssertUnwindSafe(solve))
        .map(|d| (d, t.elapsed().as_secs_f64() * 1e6))
        .map_err(panic_message)
}

/// Every rotational and sliding domain of a separable grid, solved in parallel.
fn separable_domains(
    sample: Option<crate::model::Arch>,
    weight: crate::model::WeightModel,
    keys: &SeparableKeys,
) -> (Vec<Timed<RotationalDomain>>, Vec<Timed<SlidingDomain>>) {
    let arch_for = |g: &GeomKey, k: f64| {
        crate::model::Arch::from_valid(k, f64::from_bits(g.half_angle_deg_bits), weight, g.joints)
    };
    let rot = keys
        .rot
        .par_iter()
        .map(|g| {
            let arch = arch_for(g, f64::from_bits(g.k_bits));
            timed(|| symmetric::rotational_domain(&SymmetricCircular::new(&arch)))
        })
        .collect();
    let sld = keys
        .sld
        .par_iter()
        .map(|(g, mu_bits)| {
            // H^s does not depend on K; any K > 1 gives the same joints and weights.
            let arch = arch_for(g, sample.map_or(2.0, |a| a.k.max(1.0 + 1e-9)));
            let phi = crate::model::Friction::new(f64::from_bits(*mu_bits))
                .unwrap_or(crate::model::Friction::INFINITE)
                .angle();
            timed(|| symmetric::sliding_domain(&SymmetricCircular::new(&arch), phi))
        })
        .collect();
    (rot, sld)
}

/// The domains of a symmetric self-weight `state` grid, each solved once (timed; a panic
/// there marks the cases that use it as failed), and for each case the two it uses.
pub(super) struct SeparableDomains {
    keys: SeparableKeys,
    rot: Vec<Timed<RotationalDomain>>,
    sld: Vec<Timed<SlidingDomain>>,
    rot_uses: Vec<usize>,
    sld_uses: Vec<usize>,
}

impl SeparableDomains {
    /// Every distinct domain of the scenes, solved in parallel.
    pub(super) fn solve<'a>(
        scenes: impl Iterator<Item = &'a Scene> + Clone,
        weight: crate::model::WeightModel,
    ) -> Self {
        let sample = scenes.clone().next().map(|s| s.arch);
        let keys = SeparableKeys::of(scenes);
        let (rot, sld) = separable_domains(sample, weight, &keys);
        let (rot_uses, sld_uses) = keys.uses();
        SeparableDomains {
            keys,
            rot,
            sld,
            rot_uses,
            sld_uses,
        }
    }

    /// The compact rows of consecutive cases, the first of them case number `first` in the
    /// order the domains were keyed, written over `out` in parallel blocks (its buffer reused:
    /// a run's chunks write into memory already in use).
    pub(super) fn write_states(
        &self,
        cases: &[Case],
        first: usize,
        progress: &dyn Progress,
        out: &mut Vec<StateCase>,
    ) {
        out.clear();
        out.resize_with(cases.len(), StateCase::default);
        (out.par_chunks_mut(STATE_BLOCK_ROWS))
            .zip(cases.par_chunks(STATE_BLOCK_ROWS))
            .enumerate()
            .for_each(|(b, (rows, block))| {
                self.compare_block(block, first + b * STATE_BLOCK_ROWS, progress, rows)
            });
    }

    /// The compact rows of consecutive cases, written over `out` (as many), the first of them
    /// case number `first` in the order the domains were keyed: a comparison of each case's
    /// two domains. A case's solve time is its share of the block's comparisons (one clock
    /// reading per block: a comparison takes about as long as reading the clock) plus its
    /// share of both domain solves. Progress advances once per block; a stop asked for
    /// before a block skips it.
    fn compare_block(
        &self,
        cases: &[Case],
        first: usize,
        progress: &dyn Progress,
        out: &mut [StateCase],
    ) {
        if progress.stopped() {
            let why = crate::progress::Stopped.to_string();
            for (o, c) in out.iter_mut().zip(cases) {
                *o = StateCase::failed(c, why.clone());
            }
            return;
        }
        let start = Instant::now();
        for (j, (o, c)) in out.iter_mut().zip(cases).enumerate() {
            *o = self.compare(c, first + j);
        }
        let own = start.elapsed().as_secs_f64() * 1e6 / cases.len().max(1) as f64;
        for r in out.iter_mut().filter(|r| r.answer.is_some()) {
            r.solve_time_us += own;
        }
        progress.advance(cases.len() as u64);
    }

    /// The compact row of case number `n`, its solve time its share of both domain solves.
    fn compare(&self, c: &Case, n: usize) -> StateCase {
        let (ri, si) = self.keys.cases[n];
        match (&self.rot[ri], &self.sld[si]) {
            (Ok((rd, rt)), Ok((sd, st))) => {
                let answer = catch_unwind(AssertUnwindSafe(|| StateAnswer::of(rd, sd)));
                let (answer, message) = match answer {
                    Ok(a) => (Some(a), None),
                    Err(p) => (None, Some(panic_message(p))),
                };
                StateCase {
                    case_id: c.id,
                    load_case: c.load_case,
                    inputs: Inputs::of(&c.scene),
                    answer,
                    solve_time_us: rt / self.rot_uses[ri] as f64 + st / self.sld_uses[si] as f64,
                    message,
                }
            }
            (Err(m), _) | (_, Err(m)) => StateCase::failed(c, m.clone()),
        }
    }
}

/// Cases compared by one task of a separable grid: enough that reading the clock and
/// advancing the progress once per block cost nothing next to the comparisons, few enough
/// that the blocks spread over every thread.
const STATE_BLOCK_ROWS: usize = 1 << 12;

/// A symmetric self-weight `state` grid: each domain solved once, then a comparison per case.
pub(super) fn run_separable(
    cases: &[Case],
    weight: crate::model::WeightModel,
    progress: &dyn Progress,
    out: &mut Vec<StateCase>,
) {
    let domains = SeparableDomains::solve(cases.iter().map(|c| &c.scene), weight);
    domains.write_states(cases, 0, progress, out);
    debug_assert!(out.iter().all(|r| r.inputs.find == Find::State));
}
