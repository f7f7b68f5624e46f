//! The thicknesses at which an arch stands: every interval ("window") of K on which the
//! margin is non-negative, found by a scan of the margin and refined at each end.
//!
//! The set of K at which an arch stands need not be one interval. K enters the rows
//! non-linearly (joint ends, weights and load positions all move with it), and a point load
//! on a voussoir arch can move from one voussoir onto the next as K changes, so the margin
//! can fall back below zero above the collapse thickness K_c and rise again further on. A
//! root search that stops at the first sign change finds K_c, the start of the first
//! window, and nothing of what follows; the scan here finds every window wider than its
//! resolution.
//!
//! μ and λ have no such problem: the feasible set of the rows grows with μ (the Coulomb
//! cones widen) and is convex in (x, λ) jointly (every row is linear in both), so the
//! friction and load-factor finds have interval answers.

use super::roots::brent;

/// Settings of the window scan of a thickness find.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WindowSettings {
    /// Step of the scan in K (default 2e-3): no window and no gap between windows wider
    /// than this is missed.
    pub resolution: f64,
    /// The scan covers K from the lower end of the search to the larger of this and
    /// 1 + 2 (K_c − 1) (default 3, t/R_c = 1).
    pub scan_to: f64,
    /// Absolute tolerance of each window end in K (default 1e-12).
    pub tol_end: f64,
}

impl WindowSettings {
    /// The defaults.
    pub const DEFAULT: Self = WindowSettings {
        resolution: 2e-3,
        scan_to: 3.0,
        tol_end: 1e-12,
    };

    /// The upper end of a scan whose first window starts at `k_c` (if any), capped at
    /// `cap`, where the arch's family ends.
    pub fn upper_end(&self, k_c: Option<f64>, cap: f64) -> f64 {
        let reach = k_c.map_or(self.scan_to, |k| self.scan_to.max(1.0 + 2.0 * (k - 1.0)));
        reach.min(cap)
    }
}

impl Default for WindowSettings {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// A window as results hold it: (from, to), `to` `None` when the window is open at the end
/// of the scan.
pub type Span = (f64, Option<f64>);

/// True when windows say that a thicker arch than the start of the first fails again: more
/// than one window, or one that closes before the end of the scan.
pub fn fails_again(spans: &[Span]) -> bool {
    spans.len() > 1 || spans.first().is_some_and(|w| w.1.is_some())
}

/// One interval of K on which the arch stands.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Window {
    /// Smallest K of the window (the arch stands there).
    pub from: f64,
    /// Largest K of the window (the arch stands there and fails just above); `None` when the
    /// arch still stands at the upper end of the scan.
    pub to: Option<f64>,
}

/// Every window of K found in `[lo, hi]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Windows {
    /// The windows in increasing K.
    pub windows: Vec<Window>,
    /// The upper end of the scan.
    pub scanned_to: f64,
    /// The scan step.
    pub resolution: f64,
}

impl Windows {
    /// True when a thicker arch than the start of the first window fails again.
    pub fn fails_again(&self) -> bool {
        let spans: Vec<Span> = self.windows.iter().map(|w| (w.from, w.to)).collect();
        fails_again(&spans)
    }
}

/// The windows of `psi` over `[lo, hi]`: the intervals on which psi(K) ≥ 0, psi being a
/// margin of the arch (or an error `E` where it cannot be computed, which ends the scan).
///
/// The margin is sampled at steps of `settings.resolution` from `lo`; each sign change is
/// refined by Brent's method (which only needs the bracket, so a margin that jumps where a
/// load crosses a joint is handled) to `settings.tol_end`, on the side where the arch stands.
/// `first` is a root already known (the critical search's K_c): when it lies in the
/// bracket of the first rising sign change it is used as that window's start as it is, and
/// when it lies between two failing samples before any window (a window narrower than the
/// step) that window is kept, closed where the next sample fails.
pub fn scan<E>(
    psi: impl Fn(f64) -> Result<f64, E>,
    lo: f64,
    hi: f64,
    first: Option<f64>,
    settings: &WindowSettings,
) -> Result<Windows, E> {
    let steps = ((hi - lo) / settings.resolution).ceil().max(1.0) as usize;
    let at = |i: usize| {
        if i == steps {
            hi
        } else {
            lo + (hi - lo) * i as f64 / steps as f64
        }
    };
    let mut windows = Vec::new();
    let (mut k0, mut f0) = (lo, psi(lo)?);
    let mut open = (f0 >= 0.0).then_some(lo);
    for i in 1..=steps {
        let k1 = at(i);
        let f1 = psi(k1)?;
        match (f0 >= 0.0, f1 >= 0.0) {
            (false, true) => {
                let start = match first {
                    Some(k) if windows.is_empty() && (k0..=k1).contains(&k) => k,
                    _ => refine(&psi, k0, k1, f1, settings)?,
                };
                open = Some(start);
            }
            (true, false) => {
                let end = refine(&psi, k0, k1, f1, settings)?;
                windows.push(Window {
                    from: open.take().unwrap_or(k0),
                    to: Some(end),
                });
            }
            (false, false) => {
                if let Some(k) = first.filter(|&k| windows.is_empty() && k0 < k && k <= k1) {
                    let end = refine(&psi, k, k1, f1, settings)?;
                    windows.push(Window {
                        from: k,
                        to: Some(end),
                    });
                }
            }
            _ => {}
        }
        (k0, f0) = (k1, f1);
    }
    if let Some(from) = open {
        windows.push(Window { from, to: None });
    }
    Ok(Windows {
        windows,
        scanned_to: hi,
        resolution: settings.resolution,
    })
}

/// The sign change of `psi` between a and b (psi(b) = fb), on the side where psi ≥ 0.
pub fn refine<E>(
    psi: &impl Fn(f64) -> Result<f64, E>,
    a: f64,
    b: f64,
    fb: f64,
    settings: &WindowSettings,
) -> Result<f64, E> {
    let failed = std::cell::RefCell::new(None);
    let f = |k: f64| match psi(k) {
        Ok(v) => v,
        Err(e) => {
            failed.borrow_mut().get_or_insert(e);
            f64::NAN
        }
    };
    // Brent returns the end on the side of the sign of its second argument's value.
    let (x0, x1) = if fb >= 0.0 { (a, b) } else { (b, a) };
    let root = brent(f, x0, x1, settings.tol_end);
    if let Some(e) = failed.into_inner() {
        return Err(e);
    }
    Ok(root.unwrap_or(if fb >= 0.0 { b } else { a }))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn windows_of(f: impl Fn(f64) -> f64, lo: f64, hi: f64) -> Vec<(f64, Option<f64>)> {
        scan(
            |k| Ok::<_, ()>(f(k)),
            lo,
            hi,
            None,
            &WindowSettings::DEFAULT,
        )
        .unwrap()
        .windows
        .into_iter()
        .map(|w| (w.from, w.to))
        .collect()
    }

    #[test]
    fn a_margin_that_falls_and_rises_again_has_two_windows() {
        // Stands on [1.2, 1.5] and from 2.25 on, with a jump at 1.5 (a load crossing a joint).
        let f = |k: f64| {
            if k <= 1.5 { k - 1.2 } else { (k - 2.25) * 3.0 }
        };
        let w = windows_of(f, 1.0, 3.0);
        assert_eq!(w.len(), 2, "{w:?}");
        assert!((w[0].0 - 1.2).abs() < 1e-11);
        assert!((w[0].1.unwrap() - 1.5).abs() < 1e-11);
        assert!((w[1].0 - 2.25).abs() < 1e-11);
        assert_eq!(w[1].1, None);
        // Each end is on the standing side.
        assert!(f(w[0].0) >= 0.0 && f(w[0].1.unwrap()) >= 0.0 && f(w[1].0) >= 0.0);
    }

    #[test]
    fn a_window_narrower_than_the_resolution_may_be_missed_but_one_wider_is_not() {
        let wide = |k: f64| 0.004 - (k - 2.0).abs(); // 8e-3 wide
        assert_eq!(windows_of(wide, 1.0, 3.0).len(), 1);
        let w = windows_of(wide, 1.0, 3.0)[0];
        assert!((w.0 - 1.996).abs() < 1e-11 && (w.1.unwrap() - 2.004).abs() < 1e-11);
    }

    #[test]
    fn a_known_first_root_is_kept_as_it_is() {
        let f = |k: f64| k - 1.3011;
        let w = scan(
            |k| Ok::<_, ()>(f(k)),
            1.0,
            3.0,
            Some(1.3011 + 1e-14),
            &WindowSettings::DEFAULT,
        )
        .unwrap();
        assert_eq!(w.windows[0].from, 1.3011 + 1e-14);
        assert!(!w.fails_again());
    }

    #[test]
    fn a_known_root_between_two_failing_samples_keeps_its_narrow_window() {
        // Stands on [1.5003, 1.5008] only, between two samples of the 2e-3 step; the known
        // root given is inside it.
        let f = |k: f64| 0.00025 - (k - 1.50055).abs();
        assert!(windows_of(f, 1.0, 3.0).is_empty());
        let w = scan(
            |k| Ok::<_, ()>(f(k)),
            1.0,
            3.0,
            Some(1.5004),
            &WindowSettings::DEFAULT,
        )
        .unwrap();
        assert_eq!(w.windows.len(), 1);
        assert_eq!(w.windows[0].from, 1.5004);
        assert!((w.windows[0].to.unwrap() - 1.5008).abs() < 1e-11);
    }

    #[test]
    fn an_error_ends_the_scan() {
        let r = scan(
            |k| if k > 2.0 { Err("no") } else { Ok(k - 1.5) },
            1.0,
            3.0,
            None,
            &WindowSettings::DEFAULT,
        );
        assert_eq!(r, Err("no"));
    }

    #[test]
    fn the_scan_reaches_twice_the_thickness_of_a_late_collapse() {
        let s = WindowSettings::DEFAULT;
        assert_eq!(s.upper_end(Some(1.2), f64::INFINITY), 3.0);
        assert_eq!(s.upper_end(Some(2.5), f64::INFINITY), 4.0);
        assert_eq!(s.upper_end(None, 2.0), 2.0);
    }
}
