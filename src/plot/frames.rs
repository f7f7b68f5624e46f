//! Where the plotting area of a chart lies on its canvas: recorded while the chart is drawn,
//! so that a page showing the SVG can turn a click into the chart's own coordinates
//! (`archstudy explore` moves its scene to the (μ, K) clicked on a regime map).
//!
//! Recording is off unless a caller asks for it with [`capture`]; charts call [`record`]
//! once their axes are built, which costs nothing when nobody listens.

use super::XyChart;
use plotters::prelude::DrawingBackend;
use serde::Serialize;
use std::cell::RefCell;

/// The plotting area of one chart: its pixel box on the canvas (design pixels of the SVG's
/// view box) and the data ranges of its axes (both linear).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PlotFrame {
    /// Left, top, right and bottom edges of the plotting area, pixels.
    pub left: f64,
    /// Top edge, pixels.
    pub top: f64,
    /// Right edge, pixels.
    pub right: f64,
    /// Bottom edge, pixels.
    pub bottom: f64,
    /// The x value at the left and at the right edge.
    pub x: (f64, f64),
    /// The y value at the bottom and at the top edge.
    pub y: (f64, f64),
    /// True when the y axis is logarithmic: `y` then holds log10 of the values.
    pub log_y: bool,
}

impl PlotFrame {
    /// The data point at pixel (px, py), when it lies inside the plotting area.
    pub fn value_at(&self, px: f64, py: f64) -> Option<(f64, f64)> {
        let inside =
            (self.left..=self.right).contains(&px) && (self.top..=self.bottom).contains(&py);
        inside.then(|| {
            let fx = (px - self.left) / (self.right - self.left);
            let fy = (self.bottom - py) / (self.bottom - self.top);
            let y = self.y.0 + fy * (self.y.1 - self.y.0);
            (
                self.x.0 + fx * (self.x.1 - self.x.0),
                if self.log_y { 10f64.powf(y) } else { y },
            )
        })
    }
}

thread_local! {
    static FRAMES: RefCell<Option<Vec<PlotFrame>>> = const { RefCell::new(None) };
}

/// Records the plotting area of a chart whose axes span `x` and `y` (log10 of the values when
/// `log_y`), when a [`capture`] on this thread is listening.
pub(crate) fn record<DB: DrawingBackend>(
    chart: &XyChart<DB>,
    x: (f64, f64),
    y: (f64, f64),
    log_y: bool,
) {
    FRAMES.with(|f| {
        if let Some(frames) = f.borrow_mut().as_mut() {
            let (xr, yr) = chart.plotting_area().get_pixel_range();
            frames.push(PlotFrame {
                left: f64::from(xr.start),
                top: f64::from(yr.start),
                right: f64::from(xr.end),
                bottom: f64::from(yr.end),
                x,
                y,
                log_y,
            });
        }
    });
}

/// Runs `draw` (which renders figures on this thread) and returns its value with the frames
/// of the charts it drew, in drawing order.
pub fn capture<T>(draw: impl FnOnce() -> T) -> (T, Vec<PlotFrame>) {
    let before = FRAMES.with(|f| f.borrow_mut().replace(Vec::new()));
    let out = draw();
    let frames = FRAMES.with(|f| std::mem::replace(&mut *f.borrow_mut(), before));
    (out, frames.unwrap_or_default())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pixel_maps_to_the_value_of_its_place_in_the_frame() {
        let f = PlotFrame {
            left: 100.0,
            top: 50.0,
            right: 300.0,
            bottom: 250.0,
            x: (0.2, 0.8),
            y: (1.0, 1.5),
            log_y: false,
        };
        let (x, y) = f.value_at(200.0, 150.0).unwrap();
        assert!((x - 0.5).abs() < 1e-12 && (y - 1.25).abs() < 1e-12);
        let (x, y) = f.value_at(100.0, 250.0).unwrap();
        assert!((x - 0.2).abs() < 1e-12 && (y - 1.0).abs() < 1e-12);
        assert_eq!(f.value_at(99.0, 150.0), None);
        assert_eq!(f.value_at(200.0, 251.0), None);
    }

    #[test]
    fn nothing_is_recorded_outside_a_capture_and_captures_nest() {
        let ((), outer) = capture(|| {
            let ((), inner) = capture(|| ());
            assert!(inner.is_empty());
        });
        assert!(outer.is_empty());
    }
}
