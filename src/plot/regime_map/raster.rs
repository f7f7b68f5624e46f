//! The coloured regions of the regime map, classified from the located boundaries. The
//! regime is known exactly along every grid line: it is the regime of the grid points,
//! changing at the located boundary points. Inside a grid cell the boundaries are the chords
//! between the located points on the cell's edges that separate the same two regimes, and
//! the segments from the other located points to where they meet (a bifurcation of the run
//! in the cell, else the crossing of two straight boundaries through the cell, else the mean
//! of the points). A point of the cell takes the regime of the nearest stretch of the cell's
//! edges that it sees without crossing a boundary. So no region is drawn on the wrong side of
//! a located boundary, whatever the grid's size.

use super::{Crossing, RegimeMap};
use crate::plan;
use std::collections::HashMap;

/// A point in a cell's unit coordinates (s along μ, t along K, both in [0, 1]).
type Pt = (f64, f64);

/// A located change on a cell's edge.
struct Event<'a> {
    /// Place along the perimeter, counter-clockwise from the cell's (μ_i, K_j) corner: the
    /// bottom edge is [0, 1], the right edge [1, 2], the top [2, 3], the left [3, 4].
    pos: f64,
    /// Which edge (0 bottom, 1 right, 2 top, 3 left).
    edge: usize,
    /// The two regimes, in name order (the boundary it belongs to).
    pair: (&'a str, &'a str),
    /// The regime after it, walking counter-clockwise.
    after: &'a str,
}

/// The point of the perimeter at place `pos` (taken modulo 4).
fn perimeter_point(pos: f64) -> Pt {
    let p = pos.rem_euclid(4.0);
    match p {
        p if p < 1.0 => (p, 0.0),
        p if p < 2.0 => (1.0, p - 1.0),
        p if p < 3.0 => (3.0 - p, 1.0),
        p => (0.0, 4.0 - p),
    }
}

/// The place along the perimeter of a point on it (see [`Event::pos`]), None inside.
fn on_perimeter((s, t): Pt) -> Option<f64> {
    if t <= 0.0 {
        Some(s)
    } else if s >= 1.0 {
        Some(1.0 + t)
    } else if t >= 1.0 {
        Some(3.0 - s)
    } else if s <= 0.0 {
        Some(4.0 - t)
    } else {
        None
    }
}

/// True when the segments a–b and c–d cross at a point inside both.
fn segments_cross(a: Pt, b: Pt, c: Pt, d: Pt) -> bool {
    let orient = |p: Pt, q: Pt, r: Pt| (q.0 - p.0) * (r.1 - p.1) - (q.1 - p.1) * (r.0 - p.0);
    let (d1, d2) = (orient(c, d, a), orient(c, d, b));
    let (d3, d4) = (orient(a, b, c), orient(a, b, d));
    d1 * d2 < 0.0 && d3 * d4 < 0.0
}

/// The crossing of the line through a and b with the line through c and d, if inside the
/// cell.
fn line_crossing(a: Pt, b: Pt, c: Pt, d: Pt) -> Option<Pt> {
    let r = (b.0 - a.0, b.1 - a.1);
    let s = (d.0 - c.0, d.1 - c.1);
    let den = r.0 * s.1 - r.1 * s.0;
    if den.abs() < 1e-12 {
        return None;
    }
    let u = ((c.0 - a.0) * s.1 - (c.1 - a.1) * s.0) / den;
    let p = (a.0 + u * r.0, a.1 + u * r.1);
    let inside = |v: f64| (-1e-9..=1.0 + 1e-9).contains(&v);
    (inside(p.0) && inside(p.1)).then_some(p)
}

fn dist2(a: Pt, b: Pt) -> f64 {
    (a.0 - b.0).powi(2) + (a.1 - b.1).powi(2)
}

/// The cell (its lower index) of `x` in the grid `v` (clamped to the grid).
fn cell_of(v: &[f64], x: f64) -> usize {
    v.partition_point(|&g| g <= x).clamp(1, v.len() - 1) - 1
}

/// The regime map's regions as a function of (μ, K): see the module's documentation.
pub(super) struct Classifier<'a> {
    map: &'a RegimeMap,
    /// Crossings along μ on the edge from μ_i to μ_{i+1} at K_j, by (j, i).
    along_mu: HashMap<(usize, usize), Vec<&'a Crossing>>,
    /// Crossings along K on the edge from K_j to K_{j+1} at μ_i, by (i, j).
    along_k: HashMap<(usize, usize), Vec<&'a Crossing>>,
}

impl<'a> Classifier<'a> {
    /// The located crossings of a map sorted onto the edges of its grid cells.
    pub(super) fn new(map: &'a RegimeMap) -> Self {
        let mut along_mu: HashMap<(usize, usize), Vec<&Crossing>> = HashMap::new();
        let mut along_k: HashMap<(usize, usize), Vec<&Crossing>> = HashMap::new();
        if map.mu.len() >= 2 && map.k.len() >= 2 {
            for c in map.crossings_along_mu.iter().filter(|c| c.at.is_finite()) {
                if let Some(j) = plan::axis_index(&map.k, c.fixed) {
                    along_mu
                        .entry((j, cell_of(&map.mu, c.at)))
                        .or_default()
                        .push(c);
                }
            }
            for c in &map.crossings_along_k {
                if let Some(i) = plan::axis_index(&map.mu, c.fixed) {
                    along_k
                        .entry((i, cell_of(&map.k, c.at)))
                        .or_default()
                        .push(c);
                }
            }
        }
        Classifier {
            map,
            along_mu,
            along_k,
        }
    }

    fn corner(&self, i: usize, j: usize) -> Option<&'a str> {
        self.map.regimes[j * self.map.mu.len() + i].as_deref()
    }

    /// The regime drawn at (μ, K): μ = ∞ in the strip of infinite friction, a finite μ in
    /// the grid's range (clamped to it). None where no regime is known.
    pub(super) fn regime_at(&self, mu: f64, k: f64) -> Option<&'a str> {
        let (m, kk) = (&self.map.mu, &self.map.k);
        if mu.is_infinite() {
            return self.map.infinite.as_ref().and_then(|s| s.regime_at(kk, k));
        }
        if m.len() < 2 || kk.len() < 2 {
            return None;
        }
        let (i, j) = (cell_of(m, mu), cell_of(kk, k));
        let s = ((mu - m[i]) / (m[i + 1] - m[i])).clamp(0.0, 1.0);
        let t = ((k - kk[j]) / (kk[j + 1] - kk[j])).clamp(0.0, 1.0);
        self.in_cell(i, j, (s, t))
    }

    /// The located changes on the perimeter of cell (i, j), in perimeter order.
    fn events(&self, i: usize, j: usize) -> Vec<Event<'a>> {
        let (m, k) = (&self.map.mu, &self.map.k);
        let mut ev = Vec::new();
        let pair = |c: &'a Crossing| {
            let (a, b) = (c.low.as_str(), c.high.as_str());
            if a <= b { (a, b) } else { (b, a) }
        };
        let sides = [
            (self.along_mu.get(&(j, i)), 0usize),
            (self.along_k.get(&(i + 1, j)), 1),
            (self.along_mu.get(&(j + 1, i)), 2),
            (self.along_k.get(&(i, j)), 3),
        ];
        for (list, edge) in sides {
            for &c in list.into_iter().flatten() {
                let f = if edge % 2 == 0 {
                    (c.at - m[i]) / (m[i + 1] - m[i])
                } else {
                    (c.at - k[j]) / (k[j + 1] - k[j])
                };
                let f = f.clamp(0.0, 1.0);
                // Counter-clockwise: the bottom and right edges walk towards larger values.
                let (pos, after) = if edge < 2 {
                    (edge as f64 + f, c.high.as_str())
                } else {
                    (edge as f64 + 1.0 - f, c.low.as_str())
                };
                ev.push(Event {
                    pos,
                    edge,
                    pair: pair(c),
                    after,
                });
            }
        }
        ev.sort_by(|a, b| a.pos.total_cmp(&b.pos));
        ev
    }

    /// Where the boundaries that do not cross the cell meet: a bifurcation of the run in the
    /// cell, else the crossing of a boundary through the left and right edges with one
    /// through the bottom and top edges, else the mean of their points.
    fn junction(&self, i: usize, j: usize, loose: &[&Event<'a>]) -> Pt {
        let (m, k) = (&self.map.mu, &self.map.k);
        let pts: Vec<Pt> = loose.iter().map(|e| perimeter_point(e.pos)).collect();
        let centre = (
            pts.iter().map(|p| p.0).sum::<f64>() / pts.len() as f64,
            pts.iter().map(|p| p.1).sum::<f64>() / pts.len() as f64,
        );
        let bif = self
            .map
            .bifurcations
            .iter()
            .map(|b| {
                (
                    (b.mu - m[i]) / (m[i + 1] - m[i]),
                    (b.k - k[j]) / (k[j + 1] - k[j]),
                )
            })
            .filter(|p| (-1e-9..=1.0 + 1e-9).contains(&p.0) && (-1e-9..=1.0 + 1e-9).contains(&p.1))
            .min_by(|a, b| dist2(*a, centre).total_cmp(&dist2(*b, centre)));
        if let Some(b) = bif {
            return (b.0.clamp(0.0, 1.0), b.1.clamp(0.0, 1.0));
        }
        let on = |edge: usize| {
            loose
                .iter()
                .zip(&pts)
                .filter(|(e, _)| e.edge == edge)
                .map(|(_, p)| *p)
                .collect::<Vec<Pt>>()
        };
        let (b, r, t, l) = (on(0), on(1), on(2), on(3));
        if let ([l], [r], [b], [t]) = (&l[..], &r[..], &b[..], &t[..])
            && let Some(p) = line_crossing(*l, *r, *b, *t)
        {
            return p;
        }
        centre
    }

    /// The regime at unit coordinates `p` of cell (i, j).
    fn in_cell(&self, i: usize, j: usize, p: Pt) -> Option<&'a str> {
        let corners = [
            ((0.0, 0.0), self.corner(i, j)),
            ((1.0, 0.0), self.corner(i + 1, j)),
            ((1.0, 1.0), self.corner(i + 1, j + 1)),
            ((0.0, 1.0), self.corner(i, j + 1)),
        ];
        let ev = self.events(i, j);
        if ev.is_empty() {
            if corners.iter().all(|c| c.1 == corners[0].1) {
                return corners[0].1;
            }
            // Corners that differ with no located change between them: the nearest corner.
            return corners
                .iter()
                .min_by(|a, b| dist2(a.0, p).total_cmp(&dist2(b.0, p)))
                .and_then(|c| c.1);
        }
        // On an edge: the regime of the stretch of the perimeter the point is on.
        if let Some(at) = on_perimeter(p) {
            let before = ev.iter().rev().find(|e| e.pos <= at);
            return before.or(ev.last()).map(|e| e.after);
        }
        // One sample in the middle of each stretch of the perimeter between two changes.
        let n = ev.len();
        let samples: Vec<(Pt, &str)> = (0..n)
            .map(|a| {
                let end = if a + 1 < n {
                    ev[a + 1].pos
                } else {
                    ev[0].pos + 4.0
                };
                (perimeter_point(0.5 * (ev[a].pos + end)), ev[a].after)
            })
            .collect();
        let walls = self.walls(i, j, &ev);
        let sees = |q: Pt| !walls.iter().any(|&(a, b)| segments_cross(p, q, a, b));
        let nearest = |v: &mut dyn Iterator<Item = &(Pt, &'a str)>| {
            v.min_by(|a, b| dist2(a.0, p).total_cmp(&dist2(b.0, p)))
                .map(|s| s.1)
        };
        // The nearest visible sample; the nearest of all if none is visible (boundaries that
        // cross each other in the cell).
        nearest(&mut samples.iter().filter(|(q, _)| sees(*q)))
            .or_else(|| nearest(&mut samples.iter()))
    }

    /// The boundaries inside cell (i, j) as segments: chords between two changes of the same
    /// pair of regimes (paired along the perimeter, the shorter way), and segments from every
    /// other change to the junction.
    fn walls(&self, i: usize, j: usize, ev: &[Event<'a>]) -> Vec<(Pt, Pt)> {
        let mut groups: HashMap<(&str, &str), Vec<&Event<'a>>> = HashMap::new();
        for e in ev {
            groups.entry(e.pair).or_default().push(e);
        }
        let mut walls = Vec::new();
        let mut loose = Vec::new();
        for (_, g) in groups {
            if g.len() % 2 == 1 {
                loose.extend(g);
                continue;
            }
            let pt = |e: &Event| perimeter_point(e.pos);
            let chords = |off: usize| -> Vec<(Pt, Pt)> {
                (0..g.len() / 2)
                    .map(|c| {
                        let a = g[(2 * c + off) % g.len()];
                        let b = g[(2 * c + 1 + off) % g.len()];
                        (pt(a), pt(b))
                    })
                    .collect()
            };
            let len = |v: &[(Pt, Pt)]| v.iter().map(|(a, b)| dist2(*a, *b).sqrt()).sum::<f64>();
            let (a, b) = (chords(0), chords(1));
            walls.extend(if g.len() > 2 && len(&b) < len(&a) {
                b
            } else {
                a
            });
        }
        if !loose.is_empty() {
            let jn = self.junction(i, j, &loose);
            walls.extend(loose.iter().map(|e| (perimeter_point(e.pos), jn)));
        }
        walls
    }
}

impl RegimeMap {
    /// The regime drawn at (μ, K), as the figure colours it (μ = ∞: the strip of infinite
    /// friction). This is the figure's classification as data, for checks.
    pub fn regime_at(&self, mu: f64, k: f64) -> Option<&str> {
        Classifier::new(self).regime_at(mu, k)
    }

    /// The regime at every cell centre of an `nx` × `ny` raster over the grid's finite range,
    /// K-major.
    pub fn raster(&self, nx: usize, ny: usize) -> Vec<Option<&str>> {
        let (m, k) = (&self.mu, &self.k);
        let (mu0, mu1, k0, k1) = (m[0], m[m.len() - 1], k[0], k[k.len() - 1]);
        let cls = Classifier::new(self);
        let mut out = Vec::with_capacity(nx * ny);
        for jr in 0..ny {
            let kk = k0 + (k1 - k0) * (jr as f64 + 0.5) / ny as f64;
            for ir in 0..nx {
                let mm = mu0 + (mu1 - mu0) * (ir as f64 + 0.5) / nx as f64;
                out.push(cls.regime_at(mm, kk));
            }
        }
        out
    }
}
