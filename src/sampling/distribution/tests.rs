//! Tests of the probability laws against closed forms and textbook values.

use super::super::gauss::std_sf;
use super::*;

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * b.abs().max(1.0)
}

#[test]
fn quantile_inverts_cdf_for_every_continuous_law() {
    let laws = [
        Distribution::Normal { mean: 2.0, sd: 0.5 },
        Distribution::lognormal_from_median_cov(20.0, 0.3),
        Distribution::Uniform {
            from: -1.0,
            to: 3.0,
        },
        Distribution::TruncatedNormal {
            mean: 1.15,
            sd: 0.03,
            from: 1.0,
            to: 1.3,
        },
        Distribution::TruncatedNormal {
            mean: 0.0,
            sd: 1.0,
            from: -0.5,
            to: 3.0,
        },
        Distribution::Beta {
            alpha: 2.0,
            beta: 5.0,
            from: 0.3,
            to: 0.9,
        },
        Distribution::Beta {
            alpha: 0.5,
            beta: 0.5,
            from: 0.0,
            to: 1.0,
        },
        Distribution::Beta {
            alpha: 30.0,
            beta: 0.7,
            from: 0.0,
            to: 1.0,
        },
    ];
    for law in &laws {
        for u in [1e-9, 1e-4, 0.025, 0.3, 0.5, 0.77, 0.975, 1.0 - 1e-6] {
            let x = law.quantile(u);
            let back = law.cdf(x);
            // Plus what one ulp of x is worth where the density is large.
            let tol = 1e-13 + 4.0 * law.pdf(x) * f64::EPSILON * x.abs();
            assert!(
                (back - u).abs() <= tol,
                "{}: u {u} x {x} cdf {back}",
                law.describe()
            );
        }
    }
}

#[test]
fn beta_quantile_is_accurate_to_1e_14() {
    let d = Beta::new(2.5, 0.8).expect("valid shape");
    for u in [1e-12, 1e-6, 0.01, 0.2, 0.5, 0.9, 0.999_999] {
        let x = beta_quantile(&d, u);
        assert!((d.cdf(x) - u).abs() <= 1e-14 * u.max(1e-3), "u {u} x {x}");
    }
}

#[test]
fn truncated_normal_tail_quantiles_follow_survival_function() {
    // N(0, 1) on [8, 9]: Phi(8) rounds to 1, so the naive formula returns 8 or inf.
    let law = Distribution::TruncatedNormal {
        mean: 0.0,
        sd: 1.0,
        from: 8.0,
        to: 9.0,
    };
    let (qa, qb) = (std_sf(8.0), std_sf(9.0));
    for u in [1e-6, 0.1, 0.5, 0.9, 0.999] {
        let x = law.quantile(u);
        assert!((8.0..=9.0).contains(&x));
        let expected = (qa - std_sf(x)) / (qa - qb);
        assert!((expected - u).abs() < 1e-10, "u {u} x {x} F {expected}");
    }
    // Median of the tail ~ 8 + ln 2 / 8.1 (exponential approximation).
    assert!(
        (law.quantile(0.5) - 8.0848).abs() < 2e-3,
        "{}",
        law.quantile(0.5)
    );
    let mirror = Distribution::TruncatedNormal {
        mean: 0.0,
        sd: 1.0,
        from: -9.0,
        to: -8.0,
    };
    for u in [0.01, 0.5, 0.99] {
        assert!(close(mirror.quantile(u), -law.quantile(1.0 - u), 1e-9));
    }
}

#[test]
fn moments_match_closed_forms() {
    let ln = Distribution::lognormal_from_mean_sd(10.0, 2.0);
    assert!(close(ln.mean(), 10.0, 1e-14) && close(ln.sd(), 2.0, 1e-13));
    let med = Distribution::lognormal_from_median_cov(5.0, 0.2);
    assert!(close(med.quantile(0.5), 5.0, 1e-14));
    assert!(close(med.sd() / med.mean(), 0.2, 1e-14));
    let u = Distribution::Uniform { from: 1.0, to: 4.0 };
    assert!(close(u.mean(), 2.5, 1e-15) && close(u.sd(), 3.0 / 12f64.sqrt(), 1e-15));
    // Half-normal: N(0, 1) on [0, inf): mean sqrt(2/pi), var 1 - 2/pi.
    let half = Distribution::TruncatedNormal {
        mean: 0.0,
        sd: 1.0,
        from: 0.0,
        to: f64::INFINITY,
    };
    let pi = std::f64::consts::PI;
    assert!(close(half.mean(), (2.0 / pi).sqrt(), 1e-14));
    assert!(close(half.sd(), (1.0 - 2.0 / pi).sqrt(), 1e-13));
    // Symmetric truncation keeps the mean; [-1, 1]: var = 1 - 2 phi(1) / (2 Phi(1) - 1).
    let sym = Distribution::TruncatedNormal {
        mean: 3.0,
        sd: 2.0,
        from: 1.0,
        to: 5.0,
    };
    assert!(close(sym.mean(), 3.0, 1e-14));
    let var1: f64 = 1.0 - 2.0 * 0.241_970_724_519_143_37 / 0.682_689_492_137_085_9;
    assert!(close(sym.sd(), 2.0 * var1.sqrt(), 1e-13));
    let b = Distribution::Beta {
        alpha: 2.0,
        beta: 3.0,
        from: 10.0,
        to: 20.0,
    };
    assert!(close(b.mean(), 14.0, 1e-14) && close(b.sd(), 10.0 * 0.04f64.sqrt(), 1e-14));
}

#[test]
fn discrete_sorts_normalises_and_steps() {
    let d = Distribution::discrete(vec![3.0, 1.0, 2.0], vec![1.0, 2.0, 1.0]);
    let Distribution::Discrete { values, weights } = &d else {
        panic!("discrete expected");
    };
    assert_eq!(values, &[1.0, 2.0, 3.0]);
    assert_eq!(weights, &[0.5, 0.25, 0.25]);
    assert_eq!(d.quantile(0.5), 1.0);
    assert_eq!(d.quantile(0.5000001), 2.0);
    assert_eq!(d.quantile(0.99), 3.0);
    assert_eq!(d.cdf(2.5), 0.75);
    assert_eq!(d.cdf(0.5), 0.0);
    assert_eq!(d.pdf(2.0), 0.0);
    assert_eq!(d.support(), (1.0, 3.0));
    assert!(close(d.mean(), 1.75, 1e-15));
    assert!(close(d.sd(), (0.6875f64).sqrt(), 1e-15));
}

#[test]
fn densities_integrate_to_the_cdf_difference() {
    let laws = [
        Distribution::TruncatedNormal {
            mean: 1.15,
            sd: 0.03,
            from: 1.0,
            to: 1.3,
        },
        Distribution::lognormal_from_median_cov(2.0, 0.5),
        Distribution::Beta {
            alpha: 2.0,
            beta: 3.0,
            from: 1.0,
            to: 2.0,
        },
    ];
    for law in &laws {
        let (a, b) = (law.quantile(0.1), law.quantile(0.8));
        let n = 2000;
        let h = (b - a) / f64::from(n);
        // Composite Simpson rule.
        let mut s = law.pdf(a) + law.pdf(b);
        for k in 1..n {
            let w = if k % 2 == 1 { 4.0 } else { 2.0 };
            s += w * law.pdf(a + h * f64::from(k));
        }
        assert!((s * h / 3.0 - 0.7).abs() < 1e-10, "{}", law.describe());
    }
}

#[test]
fn names_supports_and_descriptions() {
    let t = Distribution::TruncatedNormal {
        mean: 1.15,
        sd: 0.03,
        from: 1.0,
        to: 1.3,
    };
    assert_eq!(
        t.describe(),
        "truncated normal, mean 1.15, sd 0.03, on [1, 1.3]"
    );
    assert_eq!(t.name(), "truncated_normal");
    assert_eq!(
        Distribution::lognormal_from_median_cov(1.0, 0.1).support(),
        (0.0, f64::INFINITY)
    );
    assert_eq!(
        Distribution::Uniform {
            from: 0.1 + 0.2,
            to: 1.0
        }
        .describe(),
        "uniform on [0.3, 1]"
    );
    let n = Distribution::Normal { mean: 0.0, sd: 1.0 };
    assert_eq!(n.support(), (f64::NEG_INFINITY, f64::INFINITY));
    assert_eq!(n.quantile(0.0), f64::NEG_INFINITY);
    assert!(
        Distribution::Normal {
            mean: 0.0,
            sd: -1.0
        }
        .cdf(0.0)
        .is_nan()
    );
}
