//! The pathfinding graph 𝒢 on the terrain lattice (§3.2.2), implicit: a vertex's edges are
//! generated when a search asks for them, never stored. Land edges run in the primitive
//! directions of the radius-r mask (32 for r = 3, 176 for r = 8), water edges likewise over
//! water, harbour edges join adjacent land and water vertices, and bridge edges join land
//! vertices across water along a mask direction.

use super::terrain::{Terrain, FORBIDDEN, LAND, WATER};
use crate::geometry::P;

/// The primitive offsets `(dx, dy)` with `max(|dx|, |dy|) ≤ r` and `gcd(|dx|, |dy|) = 1`: one
/// direction per line through the origin and a lattice vertex within the mask, nearest vertex
/// only. Sorted by angle from the +x axis.
pub fn directions(r: u32) -> Vec<[i32; 2]> {
    let r = r as i32;
    let mut out: Vec<[i32; 2]> = Vec::new();
    for dy in -r..=r {
        for dx in -r..=r {
            if (dx, dy) != (0, 0) && gcd(dx.unsigned_abs(), dy.unsigned_abs()) == 1 {
                out.push([dx, dy]);
            }
        }
    }
    out.sort_by(|a, b| (a[1] as f64).atan2(a[0] as f64).total_cmp(&(b[1] as f64).atan2(b[0] as f64)));
    out
}

fn gcd(a: u32, b: u32) -> u32 {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}

/// What a lattice edge is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum EdgeKind {
    /// Over land.
    Land,
    /// Over water.
    Water,
    /// Between adjacent land and water vertices.
    Harbour,
    /// Between land vertices across water.
    Bridge,
}

/// One step of a direction along its major axis: the vertex at or below the point, and the
/// vertex above it with the point's fraction between them when it lies between two.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Step {
    da: i64,
    db: i64,
    f: f64,
}

/// The implicit lattice graph over a terrain.
#[derive(Clone, Debug)]
pub struct Lattice {
    /// The terrain.
    pub terrain: Terrain,
    /// The mask's directions.
    pub dirs: Vec<[i32; 2]>,
    /// The steepest grade of a land edge.
    pub slope_cut: f64,
    /// O₁: the slope weight.
    pub o1: f64,
    /// The longest water span of a bridge (metres).
    pub bridge_max: f64,
    /// Weight factor of an unbuilt harbour edge (C₃).
    pub harbour_factor: f64,
    /// Weight factor of an unbuilt bridge edge (C₅).
    pub bridge_factor: f64,
    steps: Vec<Vec<Step>>,
    lens: Vec<(f64, f64)>,
    /// Per water vertex, the Chebyshev distance (in vertices, at most 255) to the nearest vertex
    /// that is not water: a water edge shorter along each axis than this runs over water only.
    open_water: Vec<u8>,
}

/// One generated edge.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Edge {
    /// The far vertex.
    pub to: u32,
    /// Its weight.
    pub weight: f64,
    /// Its kind.
    pub kind: EdgeKind,
}

impl Lattice {
    /// The lattice over `terrain` with the radius-`r` mask and its edge rules.
    pub fn new(
        terrain: Terrain,
        r: u32,
        slope_cut: f64,
        o1: f64,
        bridge_max: f64,
        harbour_factor: f64,
        bridge_factor: f64,
    ) -> Lattice {
        let dirs = directions(r);
        let nx = terrain.nx as i64;
        let mut steps = Vec::with_capacity(dirs.len());
        let mut lens = Vec::with_capacity(dirs.len());
        for d in &dirs {
            let k = d[0].abs().max(d[1].abs()) as i64;
            let len = ((d[0] * d[0] + d[1] * d[1]) as f64).sqrt() * terrain.spacing;
            lens.push((len, len / k as f64));
            let mut list = Vec::new();
            for i in 1..=k {
                let (px, py) = (d[0] as i64 * i, d[1] as i64 * i);
                let (kx, ky) = (px.div_euclid(k), py.div_euclid(k));
                let (rx, ry) = (px.rem_euclid(k), py.rem_euclid(k));
                let (db, f) = if rx != 0 {
                    (1, rx as f64 / k as f64)
                } else if ry != 0 {
                    (nx, ry as f64 / k as f64)
                } else {
                    (0, 0.0)
                };
                list.push(Step { da: ky * nx + kx, db, f });
            }
            steps.push(list);
        }
        let open_water = open_water(&terrain);
        Lattice { terrain, dirs, slope_cut, o1, bridge_max, harbour_factor, bridge_factor, steps, lens, open_water }
    }

    /// Vertex count.
    pub fn len(&self) -> usize {
        self.terrain.nx * self.terrain.ny
    }

    /// Whether there are no vertices (never, for a checked context).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// A vertex's position (metres).
    pub fn pos(&self, v: u32) -> P {
        let nx = self.terrain.nx;
        let s = self.terrain.spacing;
        [(v as usize % nx) as f64 * s, (v as usize / nx) as f64 * s]
    }

    /// A vertex's class.
    pub fn class(&self, v: u32) -> u8 {
        self.terrain.class[v as usize]
    }

    fn offset(&self, v: u32, d: [i32; 2], m: i32) -> Option<u32> {
        let nx = self.terrain.nx as i64;
        let (x, y) = (v as i64 % nx + (d[0] * m) as i64, v as i64 / nx + (d[1] * m) as i64);
        (x >= 0 && y >= 0 && x < nx && y < self.terrain.ny as i64).then(|| (y * nx + x) as u32)
    }

    /// The vertices a straight edge from `v` by `d` passes nearest to, one or two per step along
    /// its major axis (both neighbours where it passes between two), the ends excluded.
    fn samples(&self, v: u32, d: [i32; 2], out: &mut Vec<u32>) {
        out.clear();
        let k = d[0].abs().max(d[1].abs());
        let nx = self.terrain.nx as i64;
        let (x0, y0) = (v as i64 % nx, v as i64 / nx);
        for i in 1..k {
            let (num_x, num_y) = (d[0] as i64 * i as i64, d[1] as i64 * i as i64);
            let (kx, ky) = (num_x.div_euclid(k as i64), num_y.div_euclid(k as i64));
            let (rx, ry) = (num_x.rem_euclid(k as i64), num_y.rem_euclid(k as i64));
            for ox in 0..=(rx != 0) as i64 {
                for oy in 0..=(ry != 0) as i64 {
                    out.push(((y0 + ky + oy) * nx + x0 + kx + ox) as u32);
                }
            }
        }
    }

    /// The land edge from `v` in direction `k`, if every vertex it passes is land and not
    /// `blocked`, and its steepest grade is within the cut-off: weight LENGTH · max(1, O₁ ·
    /// grade). Elevations along the edge are interpolated between the two vertices it passes
    /// between at each step along its major axis.
    pub fn land_edge<B: Fn(u32) -> bool>(&self, v: u32, k: usize, blocked: &B) -> Option<f64> {
        let to = self.offset(v, self.dirs[k], 1)?;
        let t = &self.terrain;
        if t.class[to as usize] != LAND || blocked(to) {
            return None;
        }
        let (len, run) = self.lens[k];
        let limit = self.slope_cut * run;
        let mut worst: f64 = 0.0;
        let mut prev = t.z[v as usize] as f64;
        let steps = &self.steps[k];
        for (i, st) in steps.iter().enumerate() {
            let a = (v as i64 + st.da) as usize;
            let z = if st.db == 0 {
                if i + 1 < steps.len() && (t.class[a] != LAND || blocked(a as u32)) {
                    return None;
                }
                t.z[a] as f64
            } else {
                let b = (a as i64 + st.db) as usize;
                if t.class[a] != LAND || t.class[b] != LAND || blocked(a as u32) || blocked(b as u32) {
                    return None;
                }
                t.z[a] as f64 * (1.0 - st.f) + t.z[b] as f64 * st.f
            };
            let rise = (z - prev).abs();
            if rise > limit {
                return None;
            }
            worst = worst.max(rise);
            prev = z;
        }
        Some(len * (self.o1 * worst / run).max(1.0))
    }

    /// The water edge from `v` by `d`, if it runs over water only: weight LENGTH.
    fn water_edge(&self, v: u32, d: [i32; 2], buf: &mut Vec<u32>) -> Option<(u32, f64)> {
        let to = self.offset(v, d, 1)?;
        if self.class(to) != WATER {
            return None;
        }
        let k = d[0].abs().max(d[1].abs());
        if (self.open_water[v as usize] as i32) <= k {
            self.samples(v, d, buf);
        } else {
            buf.clear();
        }
        if buf.iter().any(|&u| self.class(u) != WATER) {
            return None;
        }
        Some((to, ((d[0] * d[0] + d[1] * d[1]) as f64).sqrt() * self.terrain.spacing))
    }

    /// The bridge from land vertex `v` in direction `d`: over water vertices `v + d, v + 2d, …`
    /// to the first land vertex, within the longest span.
    fn bridge_edge<B: Fn(u32) -> bool>(&self, v: u32, d: [i32; 2], blocked: &B) -> Option<(u32, f64)> {
        let step = ((d[0] * d[0] + d[1] * d[1]) as f64).sqrt() * self.terrain.spacing;
        let first = self.offset(v, d, 1)?;
        if self.class(first) != WATER {
            return None;
        }
        let mut m = 2;
        loop {
            if step * m as f64 > self.bridge_max + step {
                return None;
            }
            let u = self.offset(v, d, m)?;
            match self.class(u) {
                WATER => m += 1,
                FORBIDDEN => return None,
                _ => return (!blocked(u)).then_some((u, step * m as f64 * self.bridge_factor)),
            }
        }
    }

    /// Every edge from `v` not touching a `blocked` vertex: land or water edges in the mask's
    /// directions, harbour edges to the 8 neighbours of the other class, bridges. Edges to a
    /// vertex that `skip` marks (a search's settled vertices) are left out before their weight
    /// is computed, except bridges (whose far end is known only at the end of the span).
    pub fn edges<B: Fn(u32) -> bool, S: Fn(u32) -> bool>(
        &self,
        v: u32,
        blocked: &B,
        skip: &S,
        out: &mut Vec<Edge>,
        buf: &mut Vec<u32>,
    ) {
        out.clear();
        let class = self.class(v);
        if class == FORBIDDEN || blocked(v) {
            return;
        }
        for (k, &d) in self.dirs.iter().enumerate() {
            let near = self.offset(v, d, 1);
            let skipped = near.is_some_and(skip);
            if class == LAND {
                // A land edge ends at the adjacent vertex in its direction and a bridge needs
                // water there: when that vertex is skipped and not water, neither is of use.
                if !skipped || near.is_some_and(|u| self.class(u) == WATER) {
                    if let Some(w) = self.land_edge(v, k, blocked) {
                        out.push(Edge { to: self.offset(v, d, 1).expect("checked"), weight: w, kind: EdgeKind::Land });
                    } else if let Some((to, w)) = self.bridge_edge(v, d, blocked) {
                        out.push(Edge { to, weight: w, kind: EdgeKind::Bridge });
                    }
                }
            } else if !skipped {
                // A water edge ends at the adjacent vertex in its direction.
                if let Some((to, w)) = self.water_edge(v, d, buf) {
                    out.push(Edge { to, weight: w, kind: EdgeKind::Water });
                }
            }
            if d[0].abs() <= 1 && d[1].abs() <= 1 && !skipped {
                if let Some(u) = near {
                    let c = self.class(u);
                    if (class == LAND && c == WATER) || (class == WATER && c == LAND && !blocked(u)) {
                        let len = ((d[0] * d[0] + d[1] * d[1]) as f64).sqrt() * self.terrain.spacing;
                        out.push(Edge { to: u, weight: len * self.harbour_factor, kind: EdgeKind::Harbour });
                    }
                }
            }
        }
    }
}

/// The Chebyshev distance from every water vertex to the nearest vertex that is not water (0 on
/// land and forbidden ground, at most 255), by two chamfer passes over the 8-neighbourhood.
fn open_water(t: &Terrain) -> Vec<u8> {
    let (nx, ny) = (t.nx, t.ny);
    let mut d: Vec<u8> = t.class.iter().map(|&c| if c == WATER { 255 } else { 0 }).collect();
    let relax = |d: &mut Vec<u8>, v: usize, u: usize| {
        let through = d[u].saturating_add(1);
        if through < d[v] {
            d[v] = through;
        }
    };
    for y in 0..ny {
        for x in 0..nx {
            let v = y * nx + x;
            if x > 0 {
                relax(&mut d, v, v - 1);
            }
            if y > 0 {
                relax(&mut d, v, v - nx);
                if x > 0 {
                    relax(&mut d, v, v - nx - 1);
                }
                if x + 1 < nx {
                    relax(&mut d, v, v - nx + 1);
                }
            }
        }
    }
    for y in (0..ny).rev() {
        for x in (0..nx).rev() {
            let v = y * nx + x;
            if x + 1 < nx {
                relax(&mut d, v, v + 1);
            }
            if y + 1 < ny {
                relax(&mut d, v, v + nx);
                if x + 1 < nx {
                    relax(&mut d, v, v + nx + 1);
                }
                if x > 0 {
                    relax(&mut d, v, v + nx - 1);
                }
            }
        }
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mask_direction_counts() {
        assert_eq!(directions(1).len(), 8);
        assert_eq!(directions(3).len(), 32);
        assert_eq!(directions(8).len(), 176);
    }

    /// The open-water distance is the Chebyshev distance to the nearest non-water vertex, and a
    /// water edge found through it is the one the samples give.
    #[test]
    fn open_water_skips_only_what_is_water() {
        let n = 12;
        let mut class = vec![WATER; n * n];
        class[5 * n + 2] = LAND;
        let t = Terrain { nx: n, ny: n, spacing: 1.0, z: vec![0.0; n * n], class: class.clone() };
        let d = open_water(&t);
        for y in 0..n {
            for x in 0..n {
                let cheb = (x as i64 - 2).abs().max((y as i64 - 5).abs()) as u8;
                assert_eq!(d[y * n + x], cheb, "({x}, {y})");
            }
        }
        let l = Lattice::new(t, 4, 1.0, 1.0, 10.0, 1.0, 1.0);
        let mut buf = Vec::new();
        for v in 0..(n * n) as u32 {
            for &dir in &l.dirs {
                let fast = l.water_edge(v, dir, &mut buf);
                let slow = l.offset(v, dir, 1).filter(|&to| l.class(to) == WATER).and_then(|to| {
                    l.samples(v, dir, &mut buf);
                    buf.iter().all(|&u| l.class(u) == WATER).then_some(to)
                });
                assert_eq!(fast.map(|f| f.0), slow, "vertex {v} direction {dir:?}");
            }
        }
    }

    /// Skipping settled vertices leaves out exactly the edges that end at one of them (bridges
    /// aside), in the same order, and changes no other edge.
    #[test]
    fn skipped_vertices_lose_only_their_edges() {
        let n = 16;
        let mut class = vec![LAND; n * n];
        for y in 0..n {
            for x in 6..9 {
                class[y * n + x] = WATER;
            }
        }
        class[3 * n + 3] = FORBIDDEN;
        let z = (0..n * n).map(|v| ((v % n) as f32 * 0.3).sin() + (v / n) as f32 * 0.1).collect();
        let l = Lattice::new(Terrain { nx: n, ny: n, spacing: 1.0, z, class }, 4, 0.9, 2.0, 6.0, 3.0, 5.0);
        let skip = |u: u32| u.is_multiple_of(3) || u % 7 == 1;
        let blocked = |u: u32| u == 2 * n as u32 + 12;
        let (mut all, mut kept, mut buf) = (Vec::new(), Vec::new(), Vec::new());
        for v in 0..(n * n) as u32 {
            l.edges(v, &blocked, &|_| false, &mut all, &mut buf);
            l.edges(v, &blocked, &skip, &mut kept, &mut buf);
            let expected: Vec<Edge> =
                all.iter().copied().filter(|e| e.kind == EdgeKind::Bridge || !skip(e.to)).collect();
            assert_eq!(kept, expected, "vertex {v}");
        }
    }

    #[test]
    fn samples_cover_the_line() {
        let t = Terrain { nx: 10, ny: 10, spacing: 1.0, z: vec![0.0; 100], class: vec![LAND; 100] };
        let l = Lattice::new(t, 3, 1.0, 1.0, 10.0, 1.0, 1.0);
        let mut buf = Vec::new();
        l.samples(0, [3, 0], &mut buf);
        assert_eq!(buf, vec![1, 2]);
        l.samples(0, [3, 1], &mut buf);
        assert_eq!(buf, vec![1, 11, 2, 12]);
        let k = l.dirs.iter().position(|&d| d == [3, 1]).unwrap();
        assert!((l.land_edge(0, k, &|_| false).unwrap() - 10f64.sqrt()).abs() < 1e-12);
        assert!(l.land_edge(0, k, &|u| u == 12).is_none());
    }
}
