//! Minor-road growth (§3.3): candidates Z (nodes that have not spawned streets, and temporary
//! nodes every 1.25 ℓ along segments longer than 2 ℓ), ranked by distance to the nearest
//! nucleus times (1 − its strength); the first G(t) grow one street each in the pattern K(t),
//! under the local rules of Parish & Müller: a crossing ends the street at a new junction, an
//! end near a node snaps to it, an end near a segment makes a T, a street that would cross a
//! road a little further on is extended to it, junction angles below the minimum are refused,
//! and no minor road crosses water, forbidden ground or too steep a slope. Grid streets keep to
//! a frame (their global goal): the pattern's angle, or the nearest major road's direction.

use super::context::{Pattern, PatternKind};
use super::graph::{Class, Graph, SNAP};
use super::terrain::{Terrain, LAND};
use crate::geometry::{closest_on_segment, dist, dot, segment_intersection, sub, P};
use rand::rngs::Xoshiro256PlusPlus;
use rand::RngExt;
use std::collections::HashSet;

/// How far from a nucleus the major road giving a grid its frame may be (metres).
pub const FRAME_REACH: f64 = 300.0;

/// A growth nucleus.
#[derive(Clone, Debug, PartialEq)]
pub struct Nucleus {
    /// Position (metres).
    pub pos: P,
    /// STRENGTH(q) ∈ (0, 1].
    pub strength: f64,
    /// The step it appeared in.
    pub born: u32,
}

/// Where a candidate sits.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Seat {
    Node(u32),
    OnSegment(u32, P),
}

/// What local rules make of a proposed street segment.
enum End {
    New(P),
    Node(u32),
    Split(P),
}

/// The growth state kept between steps: temporary candidates already tried.
#[derive(Clone, Debug, Default)]
pub struct Growth {
    tried: HashSet<(i64, i64)>,
}

fn key(p: P) -> (i64, i64) {
    ((p[0] * 100.0).round() as i64, (p[1] * 100.0).round() as i64)
}

/// Everything minor growth reads and writes.
pub struct Grower<'a> {
    /// The road graph.
    pub graph: &'a mut Graph,
    /// The terrain.
    pub terrain: &'a Terrain,
    /// The nuclei.
    pub nuclei: &'a [Nucleus],
    /// The pattern K(t).
    pub pattern: &'a Pattern,
    /// The steepest grade.
    pub slope_cut: f64,
    /// The step.
    pub step: u32,
    /// Random choices.
    pub rng: &'a mut Xoshiro256PlusPlus,
    /// Candidates already tried.
    pub growth: &'a mut Growth,
}

impl Grower<'_> {
    /// Grows streets from the first `count` ranked candidates; returns the segments added.
    pub fn grow(&mut self, count: usize) -> usize {
        let spacing = self.terrain.spacing;
        let mut cands: Vec<(f64, f64, P, Seat)> = Vec::new();
        // RANK(z) = dist(q_N, z) · (1 − STRENGTH(q_N)) of the nucleus q_N nearest to z (the
        // first of equally near ones), ties by that distance.
        let rank = |p: P| -> (f64, f64) {
            self.nuclei
                .iter()
                .map(|q| (dist(q.pos, p), q.strength))
                .min_by(|a, b| a.0.total_cmp(&b.0))
                .map_or((0.0, 0.0), |(d, s)| (d * (1.0 - s), d))
        };
        for (n, node) in self.graph.nodes.iter().enumerate() {
            if !node.spawned && self.graph.road_degree(n as u32) > 0 && self.terrain.class_at(node.pos) == LAND {
                let (r, d) = rank(node.pos);
                cands.push((r, d, node.pos, Seat::Node(n as u32)));
            }
        }
        for (s, g) in self.graph.segs.iter().enumerate() {
            if !matches!(g.class, Class::Minor | Class::Major) {
                continue;
            }
            let (a, b) = self.graph.ends(s as u32);
            let len = dist(a, b);
            if len <= 2.0 * spacing {
                continue;
            }
            let k = (len / (1.25 * spacing)).floor() as usize;
            for i in 1..=k {
                let f = i as f64 / (k + 1) as f64;
                let p = [a[0] + (b[0] - a[0]) * f, a[1] + (b[1] - a[1]) * f];
                if !self.growth.tried.contains(&key(p)) {
                    let (r, d) = rank(p);
                    cands.push((r, d, p, Seat::OnSegment(s as u32, p)));
                }
            }
        }
        cands.sort_by(|x, y| {
            x.0.total_cmp(&y.0)
                .then(x.1.total_cmp(&y.1))
                .then(x.2[0].total_cmp(&y.2[0]))
                .then(x.2[1].total_cmp(&y.2[1]))
        });
        let before = self.graph.segs.len();
        for &(_, _, p, seat) in cands.iter().take(count) {
            match seat {
                Seat::Node(n) => self.graph.nodes[n as usize].spawned = true,
                Seat::OnSegment(..) => {
                    self.growth.tried.insert(key(p));
                }
            }
            self.street(seat);
        }
        self.graph.segs.len() - before
    }

    /// The base heading of a street from a seat.
    fn base_heading(&mut self, seat: Seat) -> f64 {
        match seat {
            Seat::OnSegment(s, _) => {
                let (a, b) = self.graph.ends(s);
                let side = if self.rng.random::<bool>() { 1.0 } else { -1.0 };
                (b[1] - a[1]).atan2(b[0] - a[0]) + side * std::f64::consts::FRAC_PI_2
            }
            Seat::Node(n) => {
                let mut angles: Vec<f64> = self.graph.adj[n as usize]
                    .iter()
                    .filter(|&&s| self.graph.segs[s as usize].class.is_road())
                    .map(|&s| {
                        let h = self.graph.heading(s, n);
                        h[1].atan2(h[0])
                    })
                    .collect();
                if angles.is_empty() {
                    return self.rng.random::<f64>() * std::f64::consts::TAU;
                }
                angles.sort_by(f64::total_cmp);
                let mut best = (0.0, 0.0);
                for i in 0..angles.len() {
                    let a = angles[i];
                    let b = if i + 1 < angles.len() { angles[i + 1] } else { angles[0] + std::f64::consts::TAU };
                    if b - a > best.0 {
                        best = (b - a, a + (b - a) / 2.0);
                    }
                }
                best.1
            }
        }
    }

    /// The grid frame near `p`: the direction of the trade road nearest to the nucleus nearest to
    /// `p` (within [`FRAME_REACH`]), else of the trade road nearest to `p`, else 0.
    fn frame(&self, p: P) -> f64 {
        let q = self.nuclei.iter().min_by(|a, b| dist(a.pos, p).total_cmp(&dist(b.pos, p))).map(|q| q.pos);
        for at in q.into_iter().chain([p]) {
            let nearest = self
                .graph
                .segs_near(at, FRAME_REACH)
                .into_iter()
                .filter(|&s| {
                    let c = self.graph.segs[s].class;
                    c.is_road() && c.is_trade()
                })
                .map(|s| {
                    let (a, b) = self.graph.ends(s as u32);
                    (dist(at, closest_on_segment(at, a, b).0), s, a, b)
                })
                .filter(|x| x.0 <= FRAME_REACH)
                .min_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
            if let Some((_, _, a, b)) = nearest {
                return (b[1] - a[1]).atan2(b[0] - a[0]);
            }
        }
        0.0
    }

    /// One street from a seat: up to the pattern's segment count, with branches for grids.
    fn street(&mut self, seat: Seat) {
        let p = self.pattern.clone();
        let origin = match seat {
            Seat::Node(n) => self.graph.nodes[n as usize].pos,
            Seat::OnSegment(_, q) => q,
        };
        let mut heading = self.base_heading(seat);
        if p.kind == PatternKind::Grid {
            // The grid's global goal: headings on its frame (the pattern's angle, or the
            // direction of the major road nearest to the nearest nucleus), the one nearest to the
            // base heading.
            let frame = p.angle.map_or_else(|| self.frame(origin), f64::to_radians);
            heading = (0..4)
                .map(|k| frame + k as f64 * std::f64::consts::FRAC_PI_2)
                .min_by(|a, b| ang_diff(*a, heading).total_cmp(&ang_diff(*b, heading)))
                .expect("four headings");
        }
        if p.kind == PatternKind::Radial {
            if let Some(q) = self.nuclei.iter().min_by(|a, b| dist(a.pos, origin).total_cmp(&dist(b.pos, origin))) {
                let d = sub(origin, q.pos);
                if d[0].hypot(d[1]) > 1.0 {
                    let radial = d[1].atan2(d[0]);
                    // Along or across the radial direction, whichever is nearer the base heading.
                    let options = [radial, radial + std::f64::consts::FRAC_PI_2, radial - std::f64::consts::FRAC_PI_2];
                    heading = options
                        .into_iter()
                        .min_by(|a, b| ang_diff(*a, heading).total_cmp(&ang_diff(*b, heading)))
                        .expect("three options");
                }
            }
        }
        let mut queue: Vec<(Seat, f64)> = vec![(seat, heading)];
        let mut budget = p.segments as usize;
        while let Some((from, mut h)) = queue.pop() {
            let mut at = from;
            while budget > 0 {
                budget -= 1;
                match p.kind {
                    PatternKind::Organic => h += normal(self.rng) * p.heading.to_radians(),
                    PatternKind::Grid => {}
                    PatternKind::Radial => h += normal(self.rng) * p.heading.to_radians() * 0.25,
                }
                let len = p.length * (1.0 + p.jitter * (2.0 * self.rng.random::<f64>() - 1.0));
                let Some((node, stop)) = self.extend(at, h, len) else { break };
                at = Seat::Node(node);
                if p.kind == PatternKind::Grid && self.rng.random::<f64>() < p.branch {
                    let side = if self.rng.random::<bool>() { 1.0 } else { -1.0 };
                    queue.push((at, h + side * std::f64::consts::FRAC_PI_2));
                }
                // A grid street goes on through the junction it made (its global goal), so
                // crossings are 4-way; other patterns end there.
                if stop && p.kind != PatternKind::Grid {
                    break;
                }
            }
        }
    }

    /// Adds one street segment from `at` heading `h` of length `len` under the local rules;
    /// returns its far node and whether the street stops there.
    fn extend(&mut self, at: Seat, h: f64, len: f64) -> Option<(u32, bool)> {
        let p = self.pattern.clone();
        let (start, start_node, on_seg) = match at {
            Seat::Node(n) => (self.graph.nodes[n as usize].pos, Some(n), None),
            Seat::OnSegment(s, q) => (q, None, Some(s)),
        };
        let q = [start[0] + len * h.cos(), start[1] + len * h.sin()];
        let min_angle = p.min_angle.to_radians();
        let dir = [h.cos(), h.sin()];
        // The angle to the streets at the start.
        if let Some(n) = start_node {
            for &s in &self.graph.adj[n as usize] {
                if self.graph.segs[s as usize].class.is_road()
                    && dot(self.graph.heading(s, n), dir).clamp(-1.0, 1.0).acos() < min_angle
                {
                    return None;
                }
            }
        }
        let (end, stop) = self.constrain(start, q, start_node, on_seg, min_angle, p.snap, p.extend)?;
        let end_pos = match end {
            End::New(x) | End::Split(x) => x,
            End::Node(n) => self.graph.nodes[n as usize].pos,
        };
        if dist(start, end_pos) < self.terrain.spacing / 4.0 || !self.passable(start, end_pos) {
            return None;
        }
        let a = match at {
            Seat::Node(n) => n,
            Seat::OnSegment(..) => self.graph.node_at(start, true),
        };
        let b = match end {
            End::Node(n) => n,
            End::New(x) | End::Split(x) => self.graph.node_at(x, true),
        };
        if a == b || self.graph.find(a, b).is_some() {
            return None;
        }
        self.graph.nodes[a as usize].spawned = true;
        let chain = self.graph.insert(a, b, Class::Minor, 1.0, self.step);
        let last = *chain.last().expect("a chain has ends");
        Some((last, stop || chain.len() > 2))
    }

    /// The local rules for a proposed segment `start → q` (Parish & Müller's, in their order):
    /// the first crossing ends it at a junction; else an end near a node snaps to it; else an
    /// end near a segment makes a T; else, if the street continued by `reach` would cross a
    /// road, it is extended to that crossing (closing a block).
    #[allow(clippy::too_many_arguments)]
    fn constrain(
        &self,
        start: P,
        q: P,
        from: Option<u32>,
        on_seg: Option<u32>,
        min_angle: f64,
        snap: f64,
        reach: f64,
    ) -> Option<(End, bool)> {
        let touches = |s: u32| {
            let g = &self.graph.segs[s as usize];
            Some(s) == on_seg || from.is_some_and(|n| g.a == n || g.b == n)
        };
        if let Some((s, x)) = self.first_crossing(start, q, &touches) {
            return self.at_crossing(start, q, s, x, from, on_seg, min_angle, snap);
        }
        if let Some(&n) =
            self.graph.nodes_near(q, snap).iter().filter(|&&n| Some(n) != from && self.graph.road_degree(n) > 0).min_by(
                |&&a, &&b| {
                    dist(self.graph.nodes[a as usize].pos, q).total_cmp(&dist(self.graph.nodes[b as usize].pos, q))
                },
            )
        {
            let to = self.graph.nodes[n as usize].pos;
            if self.clear(start, to, from, on_seg, Some(n)) && self.end_angle_ok(n, start, min_angle) {
                return Some((End::Node(n), true));
            }
            return None;
        }
        for s in self.graph.segs_near(q, snap) {
            let s = s as u32;
            if !self.graph.segs[s as usize].class.is_road() || touches(s) {
                continue;
            }
            let (c, d) = self.graph.ends(s);
            let (x, t) = closest_on_segment(q, c, d);
            if t > 0.0 && t < 1.0 && dist(x, q) <= snap {
                if self.clear(start, x, from, on_seg, None) && crosses_at(start, q, c, d, min_angle) {
                    return Some((End::Split(x), true));
                }
                return None;
            }
        }
        let len = dist(start, q);
        if reach > 0.0 && len > 0.0 {
            let far = [q[0] + (q[0] - start[0]) / len * reach, q[1] + (q[1] - start[1]) / len * reach];
            if let Some((s, x)) = self.first_crossing(q, far, &touches) {
                if let Some(end) = self.at_crossing(start, far, s, x, from, on_seg, min_angle, snap) {
                    return Some(end);
                }
            }
        }
        Some((End::New(q), false))
    }

    /// The first road segment `a → b` crosses (after `a`), not one `touches` accepts, with the
    /// crossing point.
    fn first_crossing(&self, a: P, b: P, touches: &dyn Fn(u32) -> bool) -> Option<(u32, P)> {
        let mid = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
        let mut first: Option<(f64, u32, P)> = None;
        for s in self.graph.segs_near(mid, dist(a, b) / 2.0 + 1.0) {
            let s = s as u32;
            if !self.graph.segs[s as usize].class.is_road() || touches(s) {
                continue;
            }
            let (c, d) = self.graph.ends(s);
            if let Some((t, _)) = segment_intersection(a, b, c, d) {
                if t > 1e-6 && first.is_none_or(|f| t < f.0) {
                    first = Some((t, s, [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t]));
                }
            }
        }
        first.map(|f| (f.1, f.2))
    }

    /// The end of a street `start → q` that crosses segment `s` at `x`: a junction at `x`, or the
    /// segment's end node when `x` is near it (meeting that node's streets at the minimum angle
    /// too); `None` when the angle at the crossing is too small.
    #[allow(clippy::too_many_arguments)]
    fn at_crossing(
        &self,
        start: P,
        q: P,
        s: u32,
        x: P,
        from: Option<u32>,
        on_seg: Option<u32>,
        min_angle: f64,
        snap: f64,
    ) -> Option<(End, bool)> {
        let (c, d) = self.graph.ends(s);
        if !crosses_at(start, q, c, d, min_angle) {
            return None;
        }
        let g = &self.graph.segs[s as usize];
        let near = snap.min(dist(c, d) / 3.0).max(SNAP);
        let end = if dist(x, c) <= near {
            End::Node(g.a)
        } else if dist(x, d) <= near {
            End::Node(g.b)
        } else {
            End::Split(x)
        };
        // Snapped to a node, the street meets that node's other streets too.
        if let End::Node(n) = end {
            let to = self.graph.nodes[n as usize].pos;
            if !(self.clear(start, to, from, on_seg, Some(n)) && self.end_angle_ok(n, start, min_angle)) {
                return None;
            }
        }
        Some((end, true))
    }

    /// No road segment crosses `a → b` (other than at `from`, `on_seg` or the node `to`).
    fn clear(&self, a: P, b: P, from: Option<u32>, on_seg: Option<u32>, to: Option<u32>) -> bool {
        let mid = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
        self.graph.segs_near(mid, dist(a, b) / 2.0 + 1.0).into_iter().all(|s| {
            let g = &self.graph.segs[s];
            if !g.class.is_road() || Some(s as u32) == on_seg {
                return true;
            }
            if [from, to].iter().flatten().any(|&n| g.a == n || g.b == n) {
                return true;
            }
            let (c, d) = self.graph.ends(s as u32);
            segment_intersection(a, b, c, d).is_none_or(|(t, _)| !(1e-6..=1.0 - 1e-6).contains(&t))
        })
    }

    fn end_angle_ok(&self, n: u32, from: P, min_angle: f64) -> bool {
        let p = self.graph.nodes[n as usize].pos;
        let v = sub(from, p);
        let l = v[0].hypot(v[1]).max(1e-12);
        let v = [v[0] / l, v[1] / l];
        self.graph.adj[n as usize].iter().all(|&s| {
            !self.graph.segs[s as usize].class.is_road()
                || dot(self.graph.heading(s, n), v).clamp(-1.0, 1.0).acos() >= min_angle
        })
    }

    /// Land all along, within the slope cut-off (minor roads never bridge).
    fn passable(&self, a: P, b: P) -> bool {
        let step = self.terrain.spacing / 2.0;
        let n = (dist(a, b) / step).ceil().max(1.0) as usize;
        let mut prev = self.terrain.elevation(a);
        for i in 0..=n {
            let f = i as f64 / n as f64;
            let p = [a[0] + (b[0] - a[0]) * f, a[1] + (b[1] - a[1]) * f];
            if self.terrain.class_at(p) != LAND {
                return false;
            }
            let z = self.terrain.elevation(p);
            if i > 0 && (z - prev).abs() / (dist(a, b) / n as f64) > self.slope_cut {
                return false;
            }
            prev = z;
        }
        true
    }
}

/// Whether `start → q` meets the line of `c → d` at an angle of at least `min_angle`.
fn crosses_at(start: P, q: P, c: P, d: P, min_angle: f64) -> bool {
    let (u, v) = (sub(d, c), sub(q, start));
    let cos = (dot(u, v) / (u[0].hypot(u[1]) * v[0].hypot(v[1])).max(1e-12)).abs().clamp(0.0, 1.0);
    cos.acos() >= min_angle
}

fn ang_diff(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(std::f64::consts::TAU);
    d.min(std::f64::consts::TAU - d)
}

/// A standard normal draw (Box–Muller).
fn normal(rng: &mut Xoshiro256PlusPlus) -> f64 {
    let u = 1.0 - rng.random::<f64>();
    let v = rng.random::<f64>();
    (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grow::context::Context;
    use rand::SeedableRng;

    /// A street that crosses a segment next to its end node snaps to that node only where it
    /// meets the node's other streets at the minimum angle: here it would run 0.6° beside one.
    #[test]
    fn a_crossing_snapped_to_a_node_keeps_the_minimum_angle() {
        let ctx = Context::from_toml("size = [200, 200]").unwrap();
        let terrain = Terrain { nx: 11, ny: 11, spacing: 20.0, z: vec![0.0; 121], class: vec![LAND; 121] };
        let mut graph = Graph::new(ctx.size);
        let c = graph.node_at([50.0, 50.0], true);
        let d = graph.node_at([50.0, 150.0], true);
        let e = graph.node_at([150.0, 54.0], true);
        graph.insert(c, d, Class::Minor, 1.0, 0);
        graph.insert(c, e, Class::Minor, 1.0, 0);
        let start = graph.node_at([110.0, 53.0], true);
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(1);
        let mut growth = Growth::default();
        let pattern = ctx.pattern(0).clone();
        let mut g = Grower {
            graph: &mut graph,
            terrain: &terrain,
            nuclei: &[],
            pattern: &pattern,
            slope_cut: 0.15,
            step: 1,
            rng: &mut rng,
            growth: &mut growth,
        };
        assert!(g.extend(Seat::Node(start), std::f64::consts::PI, 80.0).is_none());
        // From the north-east it crosses c–d 6.7 m from c at wide angles to c's streets: it snaps.
        let start = g.graph.node_at([90.0, 110.0], true);
        let h = (50.0f64 - 110.0).atan2(45.0 - 90.0);
        assert_eq!(g.extend(Seat::Node(start), h, 80.0).map(|r| r.0), Some(c));
    }
}
