//! Sampling designs on the unit cube with random access: point `i` is a pure function of
//! `(method, seed, n, dims, i)`, so any slice of a plan can be built on its own and the samples
//! do not depend on the number of threads or shards.

use super::gauss::{std_cdf, std_inv_cdf};
use sobol_qmc::Sobol;
use sobol_qmc::params::JoeKuoD6;

/// The largest number of uncertain inputs (coordinates) of one design.
pub const MAX_DIMS: usize = 64;

/// Bits of a Sobol coordinate before the fill of the last cell.
const SOBOL_BITS: usize = 32;

/// How the unit points of a design are placed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// Owen-scrambled Sobol' points (Joe–Kuo direction numbers): a prefix of `2^m` points is a
    /// `(t, m, s)`-net.
    Sobol,
    /// Latin hypercube: each of the `n` equal strata of every coordinate holds one point.
    Lhs,
    /// Independent uniform points (plain Monte Carlo).
    Random,
}

impl Method {
    /// The method's identifier: `sobol`, `lhs` or `random`.
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Sobol => "sobol",
            Self::Lhs => "lhs",
            Self::Random => "random",
        }
    }

    /// The method named `s` (`sobol`, `lhs` or `random`), or `None`.
    pub fn parse(s: &str) -> Option<Self> {
        match s {
            "sobol" => Some(Self::Sobol),
            "lhs" => Some(Self::Lhs),
            "random" => Some(Self::Random),
            _ => None,
        }
    }
}

/// A design of `n` points in the open unit cube `(0, 1)^dims`.
#[derive(Debug, Clone)]
pub struct Design {
    /// How the points are placed.
    pub method: Method,
    /// The seed of the scrambling, permutations and jitter.
    pub seed: u64,
    /// Number of points (`<= 2^32`).
    pub n: u64,
    /// Number of coordinates (`<= MAX_DIMS`).
    pub dims: usize,
    /// Sobol direction numbers, `directions[j][k]` for bit `k` of the index (empty otherwise).
    directions: Vec<[u32; SOBOL_BITS]>,
    /// Per-coordinate keys of the scramble or permutation.
    keys: Vec<u64>,
}

impl Design {
    /// A design of `n` points in `dims` coordinates.
    ///
    /// # Panics
    /// If `dims > MAX_DIMS` or `n > 2^32` (both are checked where a study is read).
    pub fn new(method: Method, seed: u64, n: u64, dims: usize) -> Self {
        assert!(
            dims <= MAX_DIMS,
            "a design has at most {MAX_DIMS} dimensions"
        );
        assert!(n <= 1 << 32, "a design has at most 2^32 points");
        let directions = if method == Method::Sobol && dims > 0 {
            <Sobol<u32>>::init_direction_vals::<u32, JoeKuoD6>(dims, SOBOL_BITS, &JoeKuoD6::MINIMAL)
                .into_iter()
                .map(|v| {
                    let mut d = [0_u32; SOBOL_BITS];
                    for (slot, x) in d.iter_mut().zip(v) {
                        *slot = x;
                    }
                    d
                })
                .collect()
        } else {
            Vec::new()
        };
        let keys = (0..dims as u64)
            .map(|j| mix64(mix64(seed ^ 0x6a09_e667_f3bc_c908) ^ j))
            .collect();
        Self {
            method,
            seed,
            n,
            dims,
            directions,
            keys,
        }
    }

    /// Point `i` (`< n`) written to `out[..dims]`; every coordinate is strictly inside `(0, 1)`.
    pub fn point(&self, i: u64, out: &mut [f64]) {
        debug_assert!(i < self.n.max(1), "point {i} of a design of {}", self.n);
        debug_assert!(out.len() >= self.dims);
        for (j, slot) in out.iter_mut().take(self.dims).enumerate() {
            *slot = match self.method {
                Method::Sobol => self.sobol(i, j),
                Method::Lhs => self.lhs(i, j),
                Method::Random => random_unit(self.seed, i, j as u64),
            };
        }
    }

    /// Owen-scrambled Sobol coordinate `j` of point `i`, the last `2^-32` cell filled uniformly.
    fn sobol(&self, i: u64, j: usize) -> f64 {
        let dirs = &self.directions[j];
        let mut x = 0_u32;
        let mut bits = i;
        let mut k = 0;
        while bits != 0 && k < SOBOL_BITS {
            if bits & 1 == 1 {
                x ^= dirs[k];
            }
            bits >>= 1;
            k += 1;
        }
        let key = self.keys[j];
        let scrambled = owen_scramble(x, (key >> 32) as u32);
        // 20 further bits of a uniform fill and a final half-bit: an odd 53-bit integer.
        let fill = mix64(key ^ mix64(i ^ 0xbb67_ae85_84ca_a73b)) >> 44;
        let m = (u64::from(scrambled) << 21) | (fill << 1) | 1;
        m as f64 * TWO_POW_M53
    }

    /// Latin hypercube coordinate `j` of point `i`: stratum `pi_j(i)`, jittered inside it.
    fn lhs(&self, i: u64, j: usize) -> f64 {
        let key = self.keys[j];
        let stratum = permute(i, self.n, key as u32);
        // Few enough jitter bits that `stratum + v` and its division by n stay in the stratum.
        let n_bits = 64 - self.n.leading_zeros();
        let f = 50 - n_bits;
        let k = mix64(key ^ mix64(i ^ 0x3c6e_f372_fe94_f82b)) >> (64 - f);
        let v = (k as f64 + 0.5) / (1_u64 << f) as f64;
        (stratum as f64 + v) / self.n as f64
    }
}

/// `2^-53`.
const TWO_POW_M53: f64 = 1.0 / 9_007_199_254_740_992.0;

/// The SplitMix64 finaliser (Steele, Lea & Flood 2014): a bijective 64-bit mix.
pub(super) fn mix64(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// A uniform number strictly inside `(0, 1)` from the counter `(seed, i, j)`: an odd 53-bit
/// integer times `2^-53`.
pub(super) fn random_unit(seed: u64, i: u64, j: u64) -> f64 {
    let h = mix64(mix64(mix64(seed) ^ i) ^ j.wrapping_mul(0xd1b5_4a32_d192_ed03));
    (((h >> 12) << 1) | 1) as f64 * TWO_POW_M53
}

/// Nested uniform (Owen) scramble of a 32-bit fixed-point value: reverse the bits, apply the
/// Laine–Karras-style hash improved by Vegdahl (2021), reverse back. Each output bit depends
/// only on the bits above it, so the scramble keeps the net property.
fn owen_scramble(x: u32, key: u32) -> u32 {
    let mut n = x.reverse_bits();
    let seed = seed_hash(key);
    n ^= n.wrapping_mul(0x3d20_adea);
    n = n.wrapping_add(seed);
    n = n.wrapping_mul((seed >> 16) | 1);
    n ^= n.wrapping_mul(0x0552_6c56);
    n ^= n.wrapping_mul(0x53a2_2864);
    n.reverse_bits()
}

/// A 32-bit integer hash (Wellons' `lowbias32`), offset so that zero does not map to zero.
fn seed_hash(mut n: u32) -> u32 {
    n ^= 0xe6fe_3beb;
    n ^= n >> 16;
    n = n.wrapping_mul(0x7feb_352d);
    n ^= n >> 15;
    n = n.wrapping_mul(0x846c_a68b);
    n ^ (n >> 16)
}

/// Kensler's random-access permutation of `0..l` keyed by `p` ("Correlated Multi-Jittered
/// Sampling", 2013): a bijective hash on the enclosing power of two, cycle-walked into range.
fn permute(i: u64, l: u64, p: u32) -> u64 {
    if l <= 1 {
        return 0;
    }
    let w = u32::MAX >> (l - 1).leading_zeros().saturating_sub(32).min(31);
    let mut i = i as u32;
    loop {
        i ^= p;
        i = i.wrapping_mul(0xe170_893d);
        i ^= p >> 16;
        i ^= (i & w) >> 4;
        i ^= p >> 8;
        i = i.wrapping_mul(0x0929_eb3f);
        i ^= p >> 23;
        i ^= (i & w) >> 1;
        i = i.wrapping_mul(1 | (p >> 27));
        i = i.wrapping_mul(0x6935_fa69);
        i ^= (i & w) >> 11;
        i = i.wrapping_mul(0x74dc_b303);
        i ^= (i & w) >> 2;
        i = i.wrapping_mul(0x9e50_1cc3);
        i ^= (i & w) >> 2;
        i = i.wrapping_mul(0xc860_a3df);
        i &= w;
        i ^= i >> 5;
        if u64::from(i) < l {
            break;
        }
    }
    (u64::from(i) + u64::from(p)) % l
}

/// The number of model runs per base sample of the Saltelli design: `d + 2`.
pub fn saltelli_rows(d: usize) -> u64 {
    d as u64 + 2
}

/// Row `row` of the Saltelli design for first-order and total Sobol indices of `d` inputs,
/// written to `out[..d]`. `design` has `2 d` dimensions: the first `d` give matrix `A`, the
/// last `d` matrix `B`. With `j = row / (d + 2)` and block `b = row % (d + 2)`: `b = 0` is
/// `A_j`, `b = 1` is `B_j`, `b = 2 + i` is `A_j` with its column `i` taken from `B_j`.
pub fn saltelli_point(design: &Design, d: usize, row: u64, out: &mut [f64]) {
    debug_assert_eq!(design.dims, 2 * d);
    let rows = saltelli_rows(d);
    let (j, b) = (row / rows, row % rows);
    let mut ab = [0.0; MAX_DIMS];
    design.point(j, &mut ab[..2 * d]);
    let (a, bm) = ab[..2 * d].split_at(d);
    let source = if b == 1 { bm } else { a };
    out[..d].copy_from_slice(source);
    if b >= 2 {
        let i = (b - 2) as usize;
        out[i] = bm[i];
    }
}

/// Gaussian copula of two inputs: independent uniforms `(u1, u2)` become `(u1, u2')` whose
/// normal scores `(z1, z2')` have correlation `rho` (`z2' = rho z1 + sqrt(1 - rho^2) z2`).
/// `u2'` is kept strictly inside `(0, 1)`.
pub fn correlate(u1: f64, u2: f64, rho: f64) -> (f64, f64) {
    let z1 = std_inv_cdf(u1);
    let z2 = std_inv_cdf(u2);
    let z = rho * z1 + (1.0 - rho * rho).max(0.0).sqrt() * z2;
    let v = std_cdf(z).clamp(f64::MIN_POSITIVE, 1.0 - f64::EPSILON / 2.0);
    (u1, v)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn all_points(d: &Design) -> Vec<Vec<f64>> {
        (0..d.n)
            .map(|i| {
                let mut p = vec![0.0; d.dims];
                d.point(i, &mut p);
                p
            })
            .collect()
    }

    fn strata_each_hold_one(points: &[Vec<f64>], dim: usize, n: u64) -> bool {
        let mut seen = vec![false; n as usize];
        for p in points {
            let k = (p[dim] * n as f64).floor() as usize;
            if k >= seen.len() || seen[k] {
                return false;
            }
            seen[k] = true;
        }
        true
    }

    #[test]
    fn sobol_prefix_is_a_net_in_every_dimension() {
        let n = 1 << 10;
        let d = Design::new(Method::Sobol, 17, n, 12);
        let pts = all_points(&d);
        for dim in 0..d.dims {
            assert!(strata_each_hold_one(&pts, dim, n), "dimension {dim}");
        }
        // Dims 0 and 1 form a (0, 2)-sequence: every 2^5 x 2^5 elementary box holds one point.
        let mut boxes = [0_u32; 1 << 10];
        for p in &pts {
            let (a, b) = ((p[0] * 32.0) as usize, (p[1] * 32.0) as usize);
            boxes[a * 32 + b] += 1;
        }
        assert!(boxes.iter().all(|&c| c == 1));
        // Also the 2^2 x 2^8 boxes.
        let mut boxes = [0_u32; 1 << 10];
        for p in &pts {
            let (a, b) = ((p[0] * 4.0) as usize, (p[1] * 256.0) as usize);
            boxes[a * 256 + b] += 1;
        }
        assert!(boxes.iter().all(|&c| c == 1));
    }

    #[test]
    fn unscrambled_values_are_joe_kuo_sobol() {
        // Dimension 2 (m1 = 1, x + 1): directions 1/2, 3/4, 5/8, so for i = 0..8 in direct
        // (not Gray-code) order the values are XORs of those of the set bits of i.
        let d = Design::new(Method::Sobol, 0, 8, 2);
        let expected = [0.0, 0.5, 0.75, 0.25, 0.625, 0.125, 0.375, 0.875];
        for (i, e) in expected.iter().enumerate() {
            let mut x = 0_u32;
            for k in 0..3 {
                if (i >> k) & 1 == 1 {
                    x ^= d.directions[1][k];
                }
            }
            assert_eq!(f64::from(x) / 4_294_967_296.0, *e, "i {i}");
        }
    }

    #[test]
    fn lhs_puts_one_point_in_every_stratum() {
        for n in [1000, 1024, 1, 7] {
            let d = Design::new(Method::Lhs, 99, n, 5);
            let pts = all_points(&d);
            for dim in 0..5 {
                assert!(strata_each_hold_one(&pts, dim, n), "n {n} dimension {dim}");
            }
        }
    }

    #[test]
    fn permute_is_a_bijection_for_awkward_sizes() {
        for l in [2_u64, 3, 5, 64, 65, 1000, 4097] {
            let mut seen = vec![false; l as usize];
            for i in 0..l {
                let k = permute(i, l, 0xdead_beef) as usize;
                assert!(!seen[k], "l {l}");
                seen[k] = true;
            }
        }
    }

    #[test]
    fn points_are_inside_the_open_cube_and_reproducible() {
        for method in [Method::Sobol, Method::Lhs, Method::Random] {
            let a = Design::new(method, 5, 4096, 6);
            let b = Design::new(method, 5, 4096, 6);
            let c = Design::new(method, 6, 4096, 6);
            let (pa, pb, pc) = (all_points(&a), all_points(&b), all_points(&c));
            assert_eq!(pa, pb, "{}", method.as_str());
            let differ = pa.iter().zip(&pc).filter(|(x, y)| x != y).count();
            assert!(differ > 4000, "{}: {differ}", method.as_str());
            for p in &pa {
                assert!(p.iter().all(|&u| u > 0.0 && u < 1.0));
            }
            // A slice built from a fresh design equals the same rows of the whole.
            let mut q = vec![0.0; 6];
            Design::new(method, 5, 4096, 6).point(1234, &mut q);
            assert_eq!(q, pa[1234]);
            // Mean of each coordinate ~ 1/2 (Monte Carlo error ~ 0.0045).
            for dim in 0..6 {
                let mean = pa.iter().map(|p| p[dim]).sum::<f64>() / 4096.0;
                assert!((mean - 0.5).abs() < 0.02, "{} {mean}", method.as_str());
            }
        }
    }

    #[test]
    fn extreme_indices_stay_inside_the_cube() {
        let n = 1_u64 << 32;
        for method in [Method::Sobol, Method::Lhs, Method::Random] {
            let d = Design::new(method, u64::MAX, n, 3);
            let mut p = [0.0; 3];
            for i in [0, 1, n / 2, n - 2, n - 1] {
                d.point(i, &mut p);
                assert!(p.iter().all(|&u| u > 0.0 && u < 1.0), "{p:?}");
            }
        }
    }

    #[test]
    fn saltelli_rows_mix_columns_of_a_and_b() {
        let d = 3;
        let design = Design::new(Method::Sobol, 1, 16, 2 * d);
        let mut ab = [0.0; 6];
        design.point(5, &mut ab);
        let mut row = [0.0; 3];
        let base = 5 * saltelli_rows(d);
        saltelli_point(&design, d, base, &mut row);
        assert_eq!(row, [ab[0], ab[1], ab[2]]);
        saltelli_point(&design, d, base + 1, &mut row);
        assert_eq!(row, [ab[3], ab[4], ab[5]]);
        saltelli_point(&design, d, base + 3, &mut row);
        assert_eq!(row, [ab[0], ab[4], ab[2]]);
    }

    #[test]
    fn copula_gives_the_requested_normal_score_correlation() {
        let d = Design::new(Method::Sobol, 3, 1 << 14, 2);
        let mut p = [0.0; 2];
        let (mut sxy, mut sxx, mut syy) = (0.0, 0.0, 0.0);
        for i in 0..d.n {
            d.point(i, &mut p);
            let (u1, v) = correlate(p[0], p[1], 0.6);
            assert_eq!(u1, p[0]);
            let (x, y) = (std_inv_cdf(u1), std_inv_cdf(v));
            sxy += x * y;
            sxx += x * x;
            syy += y * y;
        }
        let r = sxy / (sxx * syy).sqrt();
        assert!((r - 0.6).abs() < 0.01, "{r}");
        assert!((correlate(0.3, 0.7, 1.0).1 - 0.3).abs() < 1e-15);
        assert!((correlate(0.3, 0.7, -1.0).1 - 0.7).abs() < 1e-15);
        assert!((correlate(0.3, 0.7, 0.0).1 - 0.7).abs() < 1e-15);
    }

    #[test]
    fn method_names_round_trip() {
        for m in [Method::Sobol, Method::Lhs, Method::Random] {
            assert_eq!(Method::parse(m.as_str()), Some(m));
        }
        assert_eq!(Method::parse("halton"), None);
    }
}
