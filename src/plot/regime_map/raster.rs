//! The coloured regions of the regime map: the regime at every pixel of a raster, with the
//! regions meeting where the boundaries were located.

use super::{Crossing, RegimeMap};

/// Where regime `r` ends on the edge from grid value `a` (regime `ra`) to `b` (regime `rb`)
/// at the other parameter's grid value `fixed`, as a fraction of the edge from `a`: the
/// located change out of `r` nearest to its corner, else half-way.
fn edge_fraction(
    located: &[Crossing],
    r: &str,
    (fixed, a, b): (f64, f64, f64),
    (ra, rb): (Option<&str>, Option<&str>),
) -> f64 {
    if ra == rb {
        return 0.5;
    }
    let tol = 1e-12 * (1.0 + fixed.abs());
    let on_edge = located
        .iter()
        .filter(|c| (c.fixed - fixed).abs() <= tol && c.at >= a.min(b) && c.at <= a.max(b));
    let frac = |c: &Crossing| ((c.at - a) / (b - a)).clamp(0.0, 1.0);
    let found = if ra == Some(r) {
        on_edge
            .filter(|c| c.low == r)
            .map(frac)
            .fold(None, |m: Option<f64>, f| Some(m.map_or(f, |m| m.min(f))))
    } else if rb == Some(r) {
        on_edge
            .filter(|c| c.high == r)
            .map(frac)
            .fold(None, |m: Option<f64>, f| Some(m.map_or(f, |m| m.max(f))))
    } else {
        None
    };
    found.unwrap_or(0.5)
}

/// Piecewise-linear map of [0, 1] onto itself sending `c` to 1/2.
fn warp(x: f64, c: f64) -> f64 {
    if x <= c {
        0.5 * x / c.max(1e-12)
    } else {
        0.5 + 0.5 * (x - c) / (1.0 - c).max(1e-12)
    }
}

impl RegimeMap {
    /// The regime at every cell centre of an `nx` × `ny` raster over the grid's range, K-major.
    /// Within a grid cell whose corners differ, each regime gets the bilinear interpolation of
    /// ±1 at the corners, in coordinates warped so that on every edge the interpolation
    /// changes sign at the located boundary; the largest wins (marching squares with the
    /// boundaries where they were found).
    pub(super) fn raster(&self, nx: usize, ny: usize) -> Vec<Option<&str>> {
        let (m, k) = (&self.mu, &self.k);
        let (mu0, mu1, k0, k1) = (m[0], m[m.len() - 1], k[0], k[k.len() - 1]);
        let cell = |v: &[f64], x: f64| v.partition_point(|&g| g <= x).clamp(1, v.len() - 1) - 1;
        let at = |i: usize, j: usize| self.regimes[j * m.len() + i].as_deref();
        let mut out = Vec::with_capacity(nx * ny);
        for jr in 0..ny {
            let kk = k0 + (k1 - k0) * (jr as f64 + 0.5) / ny as f64;
            let j = cell(k, kk);
            let t = (kk - k[j]) / (k[j + 1] - k[j]);
            for ir in 0..nx {
                let mm = mu0 + (mu1 - mu0) * (ir as f64 + 0.5) / nx as f64;
                let i = cell(m, mm);
                let s = (mm - m[i]) / (m[i + 1] - m[i]);
                let c = [at(i, j), at(i + 1, j), at(i, j + 1), at(i + 1, j + 1)];
                if c.iter().all(|r| *r == c[0]) {
                    out.push(c[0]);
                    continue;
                }
                let (xs, ks) = (&self.crossings_along_mu, &self.crossings_along_k);
                let mut best = (f64::NEG_INFINITY, None);
                for r in c.iter().flatten() {
                    // Coordinates warped so that regime r's field changes sign where r ends.
                    let bottom = edge_fraction(xs, r, (k[j], m[i], m[i + 1]), (c[0], c[1]));
                    let top = edge_fraction(xs, r, (k[j + 1], m[i], m[i + 1]), (c[2], c[3]));
                    let left = edge_fraction(ks, r, (m[i], k[j], k[j + 1]), (c[0], c[2]));
                    let right = edge_fraction(ks, r, (m[i + 1], k[j], k[j + 1]), (c[1], c[3]));
                    let sw = warp(s, bottom + (top - bottom) * t);
                    let tw = warp(t, left + (right - left) * s);
                    let w = [
                        (1.0 - sw) * (1.0 - tw),
                        sw * (1.0 - tw),
                        (1.0 - sw) * tw,
                        sw * tw,
                    ];
                    let f: f64 = c
                        .iter()
                        .zip(w)
                        .map(|(q, wq)| if q == &Some(*r) { wq } else { -wq })
                        .sum();
                    if f > best.0 {
                        best = (f, Some(*r));
                    }
                }
                out.push(best.1);
            }
        }
        out
    }
}
