//! Every vertex of a bounded polytope {y ∈ ℝ⁴ : a_i·y ≤ b_i} (rows of unit length), by a walk
//! along its edges from one vertex. At a vertex with tight rows T, every edge lies on three
//! independent planes of T; its direction is their generalised cross product, taken in the
//! sense that leaves no plane of T, and it ends where the first other row becomes tight.

use std::collections::{HashSet, VecDeque};

/// A vertex and the rows tight at it (within the walk's tolerance), increasing.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Vertex {
    pub y: [f64; 4],
    pub tight: Vec<usize>,
}

/// Why a walk stopped short.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum WalkError {
    /// More vertices than the walk may visit.
    TooManyVertices,
}

/// Tolerances and limits of a walk.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct WalkLimits {
    /// A row is tight when |a·y − b| ≤ this·(1 + |y|∞).
    pub tol_tight: f64,
    /// Largest number of vertices visited.
    pub max_vertices: usize,
    /// Largest number of tight rows whose triples are tried as edges at one vertex.
    pub max_tight: usize,
}

fn dot(a: &[f64; 4], y: &[f64; 4]) -> f64 {
    a[0] * y[0] + a[1] * y[1] + a[2] * y[2] + a[3] * y[3]
}

fn det3(m: [[f64; 3]; 3]) -> f64 {
    m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
}

/// The vector orthogonal to three vectors of ℝ⁴ (zero when they are dependent).
fn cross4(r: [&[f64; 4]; 3]) -> [f64; 4] {
    let mut d = [0.0; 4];
    for (j, dj) in d.iter_mut().enumerate() {
        let mut m = [[0.0; 3]; 3];
        for (i, row) in r.iter().enumerate() {
            let mut c = 0;
            for (k, v) in row.iter().enumerate() {
                if k != j {
                    m[i][c] = *v;
                    c += 1;
                }
            }
        }
        let s = if j % 2 == 0 { 1.0 } else { -1.0 };
        *dj = s * det3(m);
    }
    d
}

/// The rows tight at y.
pub(super) fn tight_rows(a: &[[f64; 4]], b: &[f64], y: &[f64; 4], tol: f64) -> Vec<usize> {
    let scale = 1.0 + y.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    (0..a.len())
        .filter(|&i| (dot(&a[i], y) - b[i]).abs() <= tol * scale)
        .collect()
}

/// Every vertex reachable from `start` (a vertex of the polytope) without leaving from a
/// vertex on a row marked `fence` (such vertices are listed, not expanded). The vertices off
/// one facet are connected through paths that rise toward the vertex farthest from it, so a
/// fence of one facet hides nothing beyond it.
pub(super) fn vertices(
    a: &[[f64; 4]],
    b: &[f64],
    fence: &[bool],
    start: [f64; 4],
    limits: &WalkLimits,
) -> Result<Vec<Vertex>, WalkError> {
    let first = Vertex {
        tight: tight_rows(a, b, &start, limits.tol_tight),
        y: start,
    };
    let mut seen: HashSet<Vec<usize>> = HashSet::new();
    seen.insert(first.tight.clone());
    let mut queue = VecDeque::from([first]);
    let mut out = Vec::new();
    let mut first_vertex = true;
    while let Some(v) = queue.pop_front() {
        let fenced = v.tight.iter().any(|&r| fence[r]);
        if fenced && !std::mem::take(&mut first_vertex) {
            out.push(v);
            continue;
        }
        first_vertex = false;
        for next in neighbours(a, b, &v, limits) {
            if seen.insert(next.tight.clone()) {
                if seen.len() > limits.max_vertices {
                    return Err(WalkError::TooManyVertices);
                }
                queue.push_back(next);
            }
        }
        out.push(v);
    }
    Ok(out)
}

/// The far ends of the edges leaving `v`.
fn neighbours(a: &[[f64; 4]], b: &[f64], v: &Vertex, limits: &WalkLimits) -> Vec<Vertex> {
    let t = &v.tight[..v.tight.len().min(limits.max_tight)];
    let scale = 1.0 + v.y.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let tol_dir = 1e-10;
    let mut out = Vec::new();
    let mut dirs: Vec<[f64; 4]> = Vec::new();
    for i in 0..t.len() {
        for j in i + 1..t.len() {
            for k in j + 1..t.len() {
                let d = cross4([&a[t[i]], &a[t[j]], &a[t[k]]]);
                let n = dot(&d, &d).sqrt();
                if n < 1e-9 {
                    continue;
                }
                for s in [1.0, -1.0] {
                    let d = [s * d[0] / n, s * d[1] / n, s * d[2] / n, s * d[3] / n];
                    if v.tight.iter().any(|&r| dot(&a[r], &d) > tol_dir) {
                        continue;
                    }
                    if dirs
                        .iter()
                        .any(|e| (0..4).all(|c| (e[c] - d[c]).abs() < 1e-9))
                    {
                        continue;
                    }
                    dirs.push(d);
                    let mut step = f64::INFINITY;
                    for r in 0..a.len() {
                        let rate = dot(&a[r], &d);
                        if rate > tol_dir && !v.tight.contains(&r) {
                            step = step.min(((b[r] - dot(&a[r], &v.y)) / rate).max(0.0));
                        }
                    }
                    if !step.is_finite() || step <= limits.tol_tight * scale {
                        continue;
                    }
                    let y = [
                        v.y[0] + step * d[0],
                        v.y[1] + step * d[1],
                        v.y[2] + step * d[2],
                        v.y[3] + step * d[3],
                    ];
                    out.push(Vertex {
                        tight: tight_rows(a, b, &y, limits.tol_tight),
                        y,
                    });
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_tesseract_has_sixteen_vertices() {
        let mut a = Vec::new();
        let mut b = Vec::new();
        for i in 0..4 {
            for s in [1.0, -1.0] {
                let mut r = [0.0; 4];
                r[i] = s;
                a.push(r);
                b.push(1.0);
            }
        }
        let limits = WalkLimits {
            tol_tight: 1e-12,
            max_vertices: 100,
            max_tight: 16,
        };
        let v = vertices(&a, &b, &[false; 8], [1.0; 4], &limits).unwrap();
        assert_eq!(v.len(), 16);
        assert!(
            v.iter()
                .all(|v| v.tight.len() == 4 && v.y.iter().all(|c| c.abs() == 1.0))
        );
    }

    #[test]
    fn the_cross_polytope_has_eight_degenerate_vertices() {
        // |y1| + |y2| + |y3| + |y4| ≤ 1: 16 rows, 8 vertices, each on 8 rows.
        let mut a = Vec::new();
        for m in 0..16 {
            let r: [f64; 4] = std::array::from_fn(|i| if m >> i & 1 == 1 { -0.5 } else { 0.5 });
            a.push(r);
        }
        let b = vec![0.5; 16];
        let limits = WalkLimits {
            tol_tight: 1e-12,
            max_vertices: 100,
            max_tight: 16,
        };
        let v = vertices(&a, &b, &[false; 16], [1.0, 0.0, 0.0, 0.0], &limits).unwrap();
        assert_eq!(v.len(), 8);
        assert!(v.iter().all(|v| v.tight.len() == 8));
    }
}
