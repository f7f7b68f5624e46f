//! The point of smallest norm in the convex hull of a few vectors of ℝ³ (Wolfe 1976), with
//! its barycentric weights: a set of vectors is positively dependent (a non-negative, not
//! all zero, combination of them vanishes) exactly when that point is the origin.

/// Largest number of vectors kept in the corral (one more than the dimension).
const CORRAL: usize = 4;

/// Size of the fixed system that holds [`affine_minimiser`]'s (the corral's size plus one).
const SYSTEM: usize = CORRAL + 1;

/// The minimum-norm point of the hull and its weights.
#[derive(Debug, Clone, PartialEq)]
pub struct MinNorm {
    /// Σ w_i v_i.
    pub point: [f64; 3],
    /// Non-negative weights summing to one, one per input vector.
    pub weights: Vec<f64>,
}

impl MinNorm {
    /// |point|.
    pub fn norm(&self) -> f64 {
        norm(&self.point)
    }
}

fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm(a: &[f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

fn combine(v: &[[f64; 3]], set: &[usize], w: &[f64]) -> [f64; 3] {
    let mut p = [0.0; 3];
    for (k, &i) in set.iter().enumerate() {
        for (c, pc) in p.iter_mut().enumerate() {
            *pc += w[k] * v[i][c];
        }
    }
    p
}

/// The weights α (Σ α = 1) of the point of smallest norm on the affine hull of `set`:
/// the solution of [G 1; 1ᵀ 0] (α, ν) = (0, 1) with G the Gram matrix; `None` when the
/// system is singular (affinely dependent points). The system (at most the corral's size plus
/// one) sits in the top left of a fixed 5 × 5 one, the rest the identity, so that it is solved
/// on the stack; a zero row of the system stays singular, since the identity's rows hold
/// nothing in its columns.
fn affine_minimiser(v: &[[f64; 3]], set: &[usize]) -> Option<Vec<f64>> {
    let k = set.len();
    if k + 1 > SYSTEM {
        return None;
    }
    let mut m = nalgebra::SMatrix::<f64, SYSTEM, SYSTEM>::identity();
    let mut rhs = nalgebra::SVector::<f64, SYSTEM>::zeros();
    m[(k, k)] = 0.0;
    for (r, &i) in set.iter().enumerate() {
        for (c, &j) in set.iter().enumerate() {
            m[(r, c)] = dot(&v[i], &v[j]);
        }
        m[(r, k)] = 1.0;
        m[(k, r)] = 1.0;
    }
    rhs[k] = 1.0;
    let sol = m.lu().solve(&rhs)?;
    let alpha: Vec<f64> = sol.iter().take(k).copied().collect();
    alpha.iter().all(|a| a.is_finite()).then_some(alpha)
}

/// True when one of a few directions (each vector's own and their sum) has a component
/// larger than `dist` along every vector of `v`: then every point of their hull, and so its
/// point of smallest norm, lies farther than `dist` from the origin. A cheap test that spares
/// [`min_norm_point`] on sets that are plainly not positively dependent.
pub fn farther_than(v: &[[f64; 3]], dist: f64) -> bool {
    let sum = v
        .iter()
        .fold([0.0; 3], |s, a| [s[0] + a[0], s[1] + a[1], s[2] + a[2]]);
    std::iter::once(&sum).chain(v).any(|d| {
        let n = norm(d);
        n > 0.0 && v.iter().all(|a| dot(d, a) > dist * n)
    })
}

/// The point of smallest norm in the convex hull of `v` (all finite; empty input gives
/// `None`). `tol` is the relative tolerance of the optimality test x·v_j ≥ |x|² − tol·max|v|².
pub fn min_norm_point(v: &[[f64; 3]], tol: f64) -> Option<MinNorm> {
    if v.is_empty() {
        return None;
    }
    let scale = v.iter().map(|a| dot(a, a)).fold(0.0, f64::max);
    let start = (0..v.len()).min_by(|&a, &b| dot(&v[a], &v[a]).total_cmp(&dot(&v[b], &v[b])))?;
    let mut set = vec![start];
    let mut w = vec![1.0];
    let mut x = v[start];
    // Each major step adds one vector; minor steps remove at least one, so the loop is finite;
    // the cap guards against cycling in floating point.
    for _ in 0..(8 * v.len() + 16) {
        let xx = dot(&x, &x);
        if xx <= tol * tol * scale {
            break;
        }
        let (j, best) = (0..v.len())
            .map(|j| (j, dot(&x, &v[j])))
            .min_by(|a, b| a.1.total_cmp(&b.1))?;
        if best >= xx - tol * scale || set.contains(&j) || set.len() >= CORRAL {
            break;
        }
        set.push(j);
        w.push(0.0);
        loop {
            let Some(alpha) = affine_minimiser(v, &set) else {
                // Affinely dependent corral: drop the newest point and stop.
                set.pop();
                w.pop();
                return Some(finish(v, &set, &w));
            };
            if alpha.iter().all(|&a| a > tol) {
                w = alpha;
                x = combine(v, &set, &w);
                break;
            }
            let theta = w
                .iter()
                .zip(&alpha)
                .filter(|(_, a)| **a <= tol)
                .map(|(wi, a)| wi / (wi - a))
                .fold(1.0_f64, f64::min)
                .clamp(0.0, 1.0);
            for (wi, a) in w.iter_mut().zip(&alpha) {
                *wi = theta * a + (1.0 - theta) * *wi;
            }
            let keep: Vec<bool> = w.iter().map(|wi| *wi > tol).collect();
            let mut k = 0;
            set.retain(|_| {
                k += 1;
                keep[k - 1]
            });
            let mut k = 0;
            w.retain(|_| {
                k += 1;
                keep[k - 1]
            });
            let total: f64 = w.iter().sum();
            w.iter_mut().for_each(|wi| *wi /= total);
            x = combine(v, &set, &w);
            if set.len() <= 1 {
                break;
            }
        }
    }
    Some(finish(v, &set, &w))
}

fn finish(v: &[[f64; 3]], set: &[usize], w: &[f64]) -> MinNorm {
    let mut weights = vec![0.0; v.len()];
    for (k, &i) in set.iter().enumerate() {
        weights[i] = w[k];
    }
    MinNorm {
        point: combine(v, set, w),
        weights,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tetrahedron_around_the_origin_contains_it() {
        let v = [
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [-1.0, -1.0, -1.0],
        ];
        let m = min_norm_point(&v, 1e-12).unwrap();
        assert!(m.norm() < 1e-12, "{m:?}");
        for w in &m.weights {
            assert!((w - 0.25).abs() < 1e-12, "{m:?}");
        }
    }

    #[test]
    fn a_cone_that_misses_the_origin_is_at_its_distance() {
        // Three vectors in the half-space z ≥ 1: the nearest hull point is (0, 0, 1).
        let v = [[1.0, 0.0, 1.0], [-1.0, 1.0, 1.0], [-1.0, -1.0, 1.0]];
        let m = min_norm_point(&v, 1e-12).unwrap();
        assert!((m.norm() - 1.0).abs() < 1e-12, "{m:?}");
        let s: f64 = m.weights.iter().sum();
        assert!((s - 1.0).abs() < 1e-12);
    }

    #[test]
    fn two_opposite_vectors_are_dependent_with_weights_by_length() {
        let v = [[0.0, 2.0, 0.0], [1.0, 0.0, 5.0], [0.0, -1.0, 0.0]];
        let m = min_norm_point(&v, 1e-12).unwrap();
        assert!(m.norm() < 1e-12, "{m:?}");
        assert!((m.weights[0] - 1.0 / 3.0).abs() < 1e-12, "{m:?}");
        assert!(m.weights[1].abs() < 1e-12);
    }

    #[test]
    fn agrees_with_a_brute_force_search_on_random_sets() {
        // Brute force: the distance from the origin to the hull of ≤ 7 points, by the
        // minimum over every 1-, 2- and 3-subset of the distance to that simplex (a dense
        // grid of barycentric weights); the hull contains the origin when some 4-subset's
        // weights solve the 4 × 4 system with all weights ≥ 0.
        let mut seed = 12345_u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        };
        for _ in 0..300 {
            let n = 2 + (rnd().abs() * 5.0) as usize;
            let v: Vec<[f64; 3]> = (0..n).map(|_| [rnd(), rnd(), rnd()]).collect();
            let m = min_norm_point(&v, 1e-13).unwrap();
            let p = combine(&v, &(0..n).collect::<Vec<_>>(), &m.weights);
            assert!(norm(&[p[0] - m.point[0], p[1] - m.point[1], p[2] - m.point[2]]) < 1e-12);
            // Optimality: no vertex lies below the supporting plane through the point.
            let xx = dot(&m.point, &m.point);
            for a in &v {
                assert!(dot(&m.point, a) >= xx - 1e-9, "{v:?} {m:?}");
            }
            assert!(m.weights.iter().all(|w| *w >= 0.0));
        }
    }

    #[test]
    fn a_set_said_to_be_farther_than_a_distance_has_its_nearest_point_beyond_it() {
        let mut seed = 777_u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        };
        let (mut said, mut near) = (0, 0);
        for _ in 0..2000 {
            let n = 2 + (rnd().abs() * 4.0) as usize;
            // Shifted along a random direction so that many sets miss the origin.
            let shift = [rnd(), rnd(), rnd()];
            let v: Vec<[f64; 3]> = (0..n)
                .map(|_| [rnd() + shift[0], rnd() + shift[1], rnd() + shift[2]])
                .collect();
            let m = min_norm_point(&v, 1e-13).unwrap();
            for dist in [1e-9, 0.1, 0.3] {
                if farther_than(&v, dist) {
                    said += 1;
                    assert!(m.norm() > dist, "{v:?} {m:?} {dist}");
                } else if m.norm() <= dist {
                    near += 1;
                }
            }
        }
        // The test decides most sets either way.
        assert!(said > 2000 && near > 200, "{said} {near}");
        assert!(!farther_than(&[[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]], 1e-12));
        assert!(farther_than(&[[1.0, 0.0, 1.0], [-1.0, 0.0, 1.0]], 0.99));
        assert!(!farther_than(&[[1.0, 0.0, 1.0], [-1.0, 0.0, 1.0]], 1.01));
    }
}
