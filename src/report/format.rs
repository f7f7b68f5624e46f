//! Number formatting for reports: every number a template prints is formatted here.

/// Decimals of thickness ratios, friction coefficients, t/R_c and thrusts in tables.
pub const VALUE_DECIMALS: usize = 10;
/// Decimals of joint angles in tables, degrees.
pub const ANGLE_DECIMALS: usize = 4;

/// A value with `d` decimals; `—` when absent or NaN, `∞` when infinite.
pub fn num(v: Option<f64>, d: usize) -> String {
    match v {
        None => "—".into(),
        Some(x) if x.is_nan() => "—".into(),
        Some(x) if x.is_infinite() => {
            if x > 0.0 {
                "∞".into()
            } else {
                "−∞".into()
            }
        }
        Some(x) => {
            let s = format!("{x:.d$}");
            // A value that rounds to zero is shown as 0, never as −0.
            match s.strip_prefix('-') {
                Some(rest) if rest.bytes().all(|b| b == b'0' || b == b'.') => rest.to_string(),
                _ => s,
            }
        }
    }
}

/// A table value (K, μ, t/R_c, H/W_half) at [`VALUE_DECIMALS`].
pub fn value(v: f64) -> String {
    num(Some(v), VALUE_DECIMALS)
}

/// A short value for figure annotations (4 decimals).
pub fn short(v: f64) -> String {
    num(Some(v), 4)
}

/// A load position in degrees: as given when the manifest wrote it (a few decimals), to
/// 0.01° when it was computed (from an x/L position, where it moves with K).
pub fn position_deg(v: f64) -> String {
    let s = given(v);
    match s.split_once('.') {
        Some((_, decimals)) if decimals.len() > 4 => format!("{v:.2}"),
        _ => s,
    }
}

/// A value to `digits` significant digits: plain from 10⁻³ to 10⁶, in exponent form beyond,
/// `∞` for infinity.
pub fn sig(v: f64, digits: usize) -> String {
    if !v.is_finite() {
        return if v.is_nan() { "—".into() } else { given(v) };
    }
    if v == 0.0 {
        return "0".into();
    }
    let mag = v.abs().log10().floor() as i32;
    if (-3..6).contains(&mag) {
        let decimals = (digits as i32 - 1 - mag).max(0) as usize;
        format!("{v:.decimals$}")
    } else {
        format!("{v:.*e}", digits.saturating_sub(1))
    }
}

/// A grid or scene value as given: shortest round-trip form, `∞` for infinity.
pub fn given(v: f64) -> String {
    if v.is_infinite() {
        "∞".into()
    } else {
        let s = format!("{v}");
        if s.contains('e') {
            format!("{v:.6e}")
        } else {
            s
        }
    }
}

/// A grid value for a label: as given when short (1.25, 0.4, ∞), else to four decimals
/// (a range axis of 191 steps gives K = 1.436842105263158; a bifurcation's K is computed).
pub fn compact(v: f64) -> String {
    let g = given(v);
    if g.len() <= 7 { g } else { short(v) }
}

/// A signed difference in scientific notation, e.g. `+2.63e-4`.
pub fn diff(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else {
        format!("{v:+.2e}")
    }
}

/// A duration in microseconds, e.g. `12.3 µs`.
pub fn micros(v: f64) -> String {
    if v.is_finite() {
        format!("{v:.1} µs")
    } else {
        "—".into()
    }
}

/// A duration in milliseconds, e.g. `12.3 ms`.
pub fn millis(v: f64) -> String {
    if v.is_finite() {
        format!("{v:.1} ms")
    } else {
        "—".into()
    }
}

/// Joint angles with faces or senses, e.g. `±54.4840° intrados, 0.0000° extrados`.
pub fn joints(angles: &[f64], what: &[String]) -> String {
    let mut out: Vec<String> = Vec::new();
    for (i, (&a, w)) in angles.iter().zip(what).enumerate() {
        if a < -1e-9
            && angles
                .iter()
                .zip(what)
                .skip(i + 1)
                .any(|(&b, v)| (a + b).abs() < 1e-9 && v == w)
        {
            continue;
        }
        let mirrored = a > 1e-9
            && angles
                .iter()
                .zip(what)
                .any(|(&b, v)| (a + b).abs() < 1e-9 && v == w);
        let sign = if mirrored { "±" } else { "" };
        out.push(format!("{sign}{} {w}", num(Some(a), ANGLE_DECIMALS) + "°"));
    }
    if out.is_empty() {
        "—".into()
    } else {
        out.join(", ")
    }
}

/// The median and a quantile of sorted data (linear interpolation).
pub fn quantile(sorted: &[f64], q: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    let pos = q * (sorted.len() - 1) as f64;
    let (i, f) = (pos.floor() as usize, pos.fract());
    if i + 1 < sorted.len() {
        sorted[i] * (1.0 - f) + sorted[i + 1] * f
    } else {
        sorted[i]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_computed_position_is_printed_to_a_hundredth_of_a_degree() {
        assert_eq!(position_deg(-19.97063320488878), "-19.97");
        assert_eq!(position_deg(30.000000000000004), "30.00");
        assert_eq!(position_deg(-45.0), "-45");
        assert_eq!(position_deg(12.5), "12.5");
    }

    #[test]
    fn a_value_that_rounds_to_zero_has_no_sign() {
        assert_eq!(num(Some(-1e-12), 4), "0.0000");
        assert_eq!(num(Some(-0.0), 2), "0.00");
        assert_eq!(num(Some(-0.00005), 4), "-0.0001");
        assert_eq!(num(Some(-2.5), 1), "-2.5");
    }

    #[test]
    fn joints_fold_symmetric_pairs() {
        let a = [-54.5, 0.0, 54.5];
        let f = ["intrados".to_string(), "extrados".into(), "intrados".into()];
        assert_eq!(joints(&a, &f), "0.0000° extrados, ±54.5000° intrados");
    }

    #[test]
    fn numbers() {
        assert_eq!(num(None, 3), "—");
        assert_eq!(num(Some(f64::INFINITY), 3), "∞");
        assert_eq!(value(1.25), "1.2500000000");
        assert_eq!(diff(2.63e-4), "+2.63e-4");
        assert_eq!(given(0.3), "0.3");
    }
}
