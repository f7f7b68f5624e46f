//! Every vertex of a bounded polytope {y ∈ ℝᴰ : a_i·y ≤ b_i} (D = 3 or 4, rows of unit length),
//! by a walk along its edges from one vertex. At a vertex with tight rows T, every edge lies
//! on D − 1 independent planes of T; its direction is their generalised cross product, taken
//! in the sense that leaves no plane of T, and it ends where the first other row becomes
//! tight.

use rustc_hash::FxHashMap;

/// A vertex and the rows tight at it (within the walk's tolerance), increasing.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Vertex<const D: usize = 4> {
    pub y: [f64; D],
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

fn dot<const D: usize>(a: &[f64; D], y: &[f64; D]) -> f64 {
    a.iter().zip(y).map(|(p, q)| p * q).sum()
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

/// The vector orthogonal to D − 1 vectors of ℝᴰ (zero when they are dependent); D = 3 or 4.
fn orth<const D: usize>(r: &[&[f64; D]]) -> [f64; D] {
    let mut out = [0.0; D];
    match D {
        3 => {
            let (a, b) = (r[0], r[1]);
            out[0] = a[1] * b[2] - a[2] * b[1];
            out[1] = a[2] * b[0] - a[0] * b[2];
            out[2] = a[0] * b[1] - a[1] * b[0];
        }
        4 => {
            let f = |v: &[f64; D]| [v[0], v[1], v[2], v[3]];
            let d = cross4([&f(r[0]), &f(r[1]), &f(r[2])]);
            out.copy_from_slice(&d[..D]);
        }
        _ => {}
    }
    out
}

/// The rows tight at y.
pub(super) fn tight_rows<const D: usize>(
    a: &[[f64; D]],
    b: &[f64],
    y: &[f64; D],
    tol: f64,
) -> Vec<usize> {
    let scale = 1.0 + y.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    (0..a.len())
        .filter(|&i| (dot(&a[i], y) - b[i]).abs() <= tol * scale)
        .collect()
}

/// Every vertex reachable from `start` (a vertex of the polytope) without leaving from a
/// vertex on a row marked `fence` (such vertices are listed, not expanded). The vertices off
/// one facet are connected through paths that rise toward the vertex farthest from it, so a
/// fence of one facet hides nothing beyond it.
pub(super) fn vertices<const D: usize>(
    a: &[[f64; D]],
    b: &[f64],
    fence: &[bool],
    start: [f64; D],
    limits: &WalkLimits,
) -> Result<Vec<Vertex<D>>, WalkError> {
    let first = Vertex {
        tight: tight_rows(a, b, &start, limits.tol_tight),
        y: start,
    };
    // Tight sets name the vertices; most edges end at a vertex already seen, so a far end's set
    // is built in scratch space and copied only when it is new. An edge found from one end is
    // not walked again from the other: each vertex keeps the directions back along the edges
    // that reached it before it is expanded.
    let mut seen: FxHashMap<Vec<usize>, usize> = FxHashMap::default();
    seen.insert(first.tight.clone(), 0);
    let mut out = vec![first];
    let mut back: Vec<Vec<[f64; D]>> = vec![Vec::new()];
    let mut scratch = Scratch::new(a.len());
    let mut too_many = false;
    let mut next = 0;
    // The vertex being expanded, copied out of `out`, which its neighbours extend.
    let mut at: Vec<usize> = Vec::new();
    while let Some(v) = out.get(next) {
        let y = v.y;
        at.clear();
        at.extend_from_slice(&v.tight);
        if next == 0 || !at.iter().any(|&r| fence[r]) {
            let known = std::mem::take(&mut back[next]);
            neighbours(
                a,
                b,
                (&y, &at),
                limits,
                &known,
                &mut scratch,
                |y, tight, d| {
                    let reverse = d.map(|c| -c);
                    if let Some(&w) = seen.get(tight) {
                        if w > next {
                            back[w].push(reverse);
                        }
                        return;
                    }
                    if out.len() >= limits.max_vertices {
                        too_many = true;
                        return;
                    }
                    seen.insert(tight.to_vec(), out.len());
                    out.push(Vertex {
                        y,
                        tight: tight.to_vec(),
                    });
                    back.push(vec![reverse]);
                },
            );
            if too_many {
                return Err(WalkError::TooManyVertices);
            }
        }
        next += 1;
    }
    Ok(out)
}

/// Space reused from vertex to vertex: a flag, a slack and a rate per row, the edge directions
/// of the current vertex and the tight set of an edge's far end.
struct Scratch<const D: usize> {
    tight: Vec<bool>,
    slack: Vec<f64>,
    rate: Vec<f64>,
    dirs: Vec<[f64; D]>,
    far: Vec<usize>,
}

impl<const D: usize> Scratch<D> {
    fn new(rows: usize) -> Self {
        Scratch {
            tight: vec![false; rows],
            slack: vec![0.0; rows],
            rate: vec![0.0; rows],
            dirs: Vec::new(),
            far: Vec::new(),
        }
    }
}

/// Calls `found` with the far end of every edge leaving `v` but those along `known`, the rows
/// tight there (increasing) and the edge's direction. The far end's residual a·y − b of each
/// row is −slack + step·rate, from the slack at `v` and the row's rate along the edge.
fn neighbours<const D: usize>(
    a: &[[f64; D]],
    b: &[f64],
    (vy, vt): (&[f64; D], &[usize]),
    limits: &WalkLimits,
    known: &[[f64; D]],
    scratch: &mut Scratch<D>,
    mut found: impl FnMut([f64; D], &[usize], [f64; D]),
) {
    let t = &vt[..vt.len().min(limits.max_tight)];
    let scale = 1.0 + vy.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let tol_dir = 1e-10;
    let Scratch {
        tight,
        slack,
        rate,
        dirs,
        far,
    } = scratch;
    for &r in vt {
        tight[r] = true;
    }
    for ((s, row), br) in slack.iter_mut().zip(a).zip(b) {
        *s = br - dot(row, vy);
    }
    dirs.clear();
    dirs.extend_from_slice(known);
    let mut edge = |d: [f64; D]| {
        let n = dot(&d, &d).sqrt();
        if n < 1e-9 {
            return;
        }
        for s in [1.0, -1.0] {
            let d: [f64; D] = std::array::from_fn(|c| s * d[c] / n);
            if vt.iter().any(|&r| dot(&a[r], &d) > tol_dir) {
                continue;
            }
            if dirs
                .iter()
                .any(|e| (0..D).all(|c| (e[c] - d[c]).abs() < 1e-9))
            {
                continue;
            }
            dirs.push(d);
            let mut step = f64::INFINITY;
            for ((rt, row), (s, t)) in rate.iter_mut().zip(a).zip(slack.iter().zip(&*tight)) {
                *rt = dot(row, &d);
                // The nearest row ahead; a product spares a division per row.
                if *rt > tol_dir && !*t {
                    let s = s.max(0.0);
                    if s < step * *rt {
                        step = s / *rt;
                    }
                }
            }
            if !step.is_finite() || step <= limits.tol_tight * scale {
                continue;
            }
            let y: [f64; D] = std::array::from_fn(|c| vy[c] + step * d[c]);
            let bound = limits.tol_tight * (1.0 + y.iter().fold(0.0_f64, |m, x| m.max(x.abs())));
            far.clear();
            far.extend((0..rate.len()).filter(|&r| (step * rate[r] - slack[r]).abs() <= bound));
            found(y, far, d);
        }
    };
    let n = t.len();
    for i in 0..n {
        for j in i + 1..n {
            if D == 3 {
                edge(orth(&[&a[t[i]], &a[t[j]]]));
                continue;
            }
            for k in j + 1..n {
                edge(orth(&[&a[t[i]], &a[t[j]], &a[t[k]]]));
            }
        }
    }
    for &r in vt {
        tight[r] = false;
    }
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
    fn the_cube_has_eight_vertices_in_three_dimensions() {
        let mut a = Vec::new();
        for i in 0..3 {
            for s in [1.0, -1.0] {
                let mut r = [0.0; 3];
                r[i] = s;
                a.push(r);
            }
        }
        let b = vec![2.0; 6];
        let limits = WalkLimits {
            tol_tight: 1e-12,
            max_vertices: 100,
            max_tight: 16,
        };
        let v = vertices(&a, &b, &[false; 6], [2.0, -2.0, 2.0], &limits).unwrap();
        assert_eq!(v.len(), 8);
        assert!(
            v.iter()
                .all(|v| v.tight.len() == 3 && v.y.iter().all(|c| c.abs() == 2.0))
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
