//! LU factors with partial pivoting of the D × D basis matrix.

/// LU factors with partial pivoting of a D × D matrix: P A = L U.
pub(super) struct Lu<const D: usize> {
    pub(super) lu: [[f64; D]; D],
    pub(super) perm: [usize; D],
}

// Index loops read like the textbook triangular solves they implement.
#[allow(clippy::needless_range_loop)]
impl<const D: usize> Lu<D> {
    /// Factorises `m`; `None` when a pivot is at most `tol_singular` times the largest entry
    /// (singular to working precision).
    pub(super) fn factor(mut m: [[f64; D]; D], tol_singular: f64) -> Option<Self> {
        let mut perm = [0; D];
        for (i, p) in perm.iter_mut().enumerate() {
            *p = i;
        }
        let scale = m
            .iter()
            .flat_map(|r| r.iter())
            .fold(0.0_f64, |s, v| s.max(v.abs()));
        if scale.is_nan() || scale <= 0.0 {
            return None;
        }
        for k in 0..D {
            let mut p = k;
            for i in k + 1..D {
                if m[i][k].abs() > m[p][k].abs() {
                    p = i;
                }
            }
            if m[p][k].is_nan() || m[p][k].abs() <= tol_singular * scale {
                return None;
            }
            m.swap(k, p);
            perm.swap(k, p);
            for i in k + 1..D {
                let f = m[i][k] / m[k][k];
                m[i][k] = f;
                for j in k + 1..D {
                    m[i][j] -= f * m[k][j];
                }
            }
        }
        Some(Lu { lu: m, perm })
    }

    /// z with A z = r.
    pub(super) fn solve(&self, r: &[f64; D]) -> [f64; D] {
        let mut z = [0.0; D];
        for i in 0..D {
            let mut s = r[self.perm[i]];
            for j in 0..i {
                s -= self.lu[i][j] * z[j];
            }
            z[i] = s;
        }
        for i in (0..D).rev() {
            let mut s = z[i];
            for j in i + 1..D {
                s -= self.lu[i][j] * z[j];
            }
            z[i] = s / self.lu[i][i];
        }
        z
    }

    /// z with Aᵀ z = r (Aᵀ = Uᵀ Lᵀ P).
    pub(super) fn solve_t(&self, r: &[f64; D]) -> [f64; D] {
        let mut w = [0.0; D];
        for i in 0..D {
            let mut s = r[i];
            for j in 0..i {
                s -= self.lu[j][i] * w[j];
            }
            w[i] = s / self.lu[i][i];
        }
        for i in (0..D).rev() {
            let mut s = w[i];
            for j in i + 1..D {
                s -= self.lu[j][i] * w[j];
            }
            w[i] = s;
        }
        let mut z = [0.0; D];
        for i in 0..D {
            z[self.perm[i]] = w[i];
        }
        z
    }
}
