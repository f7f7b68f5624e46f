//! A programme with many rows of which few bind, solved on a working set of them: solve on
//! the set, add every row the answer violates, repeat. The answer is the programme's own:
//! an optimum of a subset of the rows that satisfies all of them is an optimum of all of
//! them, a subset without a solution leaves none to the whole, and a ray of the subset that
//! no row blocks, from a point no row excludes, is a ray of the whole.

use crate::analysis::lp::{self, LpError, Settings, Solution, Status};

/// Maximises c·x subject to a\[r\]·x ≤ b\[r\] for every row r, as [`lp::maximise`] does,
/// solving on the rows `start` and the rows its answers violate. The basis indexes `a`.
pub(super) fn maximise_on_working_set<const D: usize>(
    c: &[f64; D],
    a: &[[f64; D]],
    b: &[f64],
    start: &[usize],
    settings: &Settings,
) -> Result<Solution<D>, LpError> {
    let mut set: Vec<usize> = start.to_vec();
    let mut in_set = vec![false; a.len()];
    for &r in &set {
        in_set[r] = true;
    }
    let mut sa: Vec<[f64; D]> = set.iter().map(|&r| a[r]).collect();
    let mut sb: Vec<f64> = set.iter().map(|&r| b[r]).collect();
    loop {
        let mut sol = lp::maximise(c, &sa, &sb, &settings.scaled_to(sa.len()))?;
        for k in sol.basis.iter_mut().flatten() {
            *k = set[*k];
        }
        let check_ray = match sol.status {
            Status::Optimal => false,
            Status::Unbounded => true,
            _ => return Ok(sol),
        };
        let tol = settings.tol_feasibility * (1.0 + inf_norm(&sol.x));
        let tol_ray = settings.tol_feasibility * inf_norm(&sol.ray);
        let mut added = false;
        let mut worst = 0.0_f64;
        for (r, (row, &br)) in a.iter().zip(b).enumerate() {
            let n = norm(row);
            if n == 0.0 || br == f64::INFINITY {
                continue;
            }
            let v = (dot(row, &sol.x) - br) / n;
            worst = worst.max(v);
            let blocks_ray = check_ray && dot(row, &sol.ray) / n > tol_ray;
            if !in_set[r] && (v > tol || blocks_ray) {
                in_set[r] = true;
                set.push(r);
                sa.push(*row);
                sb.push(br);
                added = true;
            }
        }
        if !added {
            sol.max_violation = worst;
            return Ok(sol);
        }
    }
}

fn dot<const D: usize>(a: &[f64; D], x: &[f64; D]) -> f64 {
    a.iter().zip(x).map(|(p, q)| p * q).sum()
}

fn norm<const D: usize>(a: &[f64; D]) -> f64 {
    dot(a, a).sqrt()
}

fn inf_norm<const D: usize>(x: &[f64; D]) -> f64 {
    x.iter().fold(0.0, |m, v| m.max(v.abs()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_abs_diff_eq;

    /// max x + y over the rows x·cos t + y·sin t ≤ 1 of many directions t: the polygon
    /// around the unit circle, whose optimum is √2 at t = 45°, is found from one row.
    #[test]
    fn same_optimum_as_the_whole_programme() {
        let n = 360;
        let a: Vec<[f64; 2]> = (0..n)
            .map(|k| {
                let t = (k as f64).to_radians();
                [t.cos(), t.sin()]
            })
            .collect();
        let b = vec![1.0; n];
        let c = [1.0, 1.0];
        let s = Settings::default();
        let whole = lp::maximise(&c, &a, &b, &s).unwrap();
        let ws = maximise_on_working_set(&c, &a, &b, &[0], &s).unwrap();
        assert_eq!(ws.status, Status::Optimal);
        assert_abs_diff_eq!(ws.objective, whole.objective, epsilon = 1e-14);
        assert_abs_diff_eq!(ws.objective, 2f64.sqrt(), epsilon = 1e-14);
        // The face of the 45° row is optimal: that row is basic, with a neighbour.
        assert!(ws.basis.contains(&Some(45)), "{:?}", ws.basis);
        assert!(ws.basis.iter().flatten().all(|&k| (44..=46).contains(&k)));
        assert!(ws.max_violation <= 1e-14);
    }

    #[test]
    fn rays_and_infeasibility_are_those_of_the_whole_programme() {
        let c = [1.0, 0.0];
        let s = Settings::default();
        // x ≤ 1 only binds once y ≤ 0 and −y ≤ 0 are in: from y ≤ 0 alone, unbounded.
        let a = [[0.0, 1.0], [1.0, 0.0], [0.0, -1.0]];
        let b = [0.0, 1.0, 0.0];
        let ws = maximise_on_working_set(&c, &a, &b, &[0], &s).unwrap();
        assert_eq!(ws.status, Status::Optimal);
        assert_abs_diff_eq!(ws.objective, 1.0, epsilon = 1e-15);
        // Without x ≤ 1 the whole programme is unbounded.
        let ws = maximise_on_working_set(&c, &a[..1], &b[..1], &[0], &s).unwrap();
        assert_eq!(ws.status, Status::Unbounded);
        // x ≥ 2 and x ≤ 1: infeasible once both are in.
        let a = [[0.0, 1.0], [-1.0, 0.0], [1.0, 0.0]];
        let b = [0.0, -2.0, 1.0];
        let ws = maximise_on_working_set(&c, &a, &b, &[0], &s).unwrap();
        assert_eq!(ws.status, Status::Infeasible);
    }
}
