//! The simulation (Alg. 1): the initial network (§3.2) and each time step — minor-road growth,
//! then traffic and major-road growth per city pair (Alg. 2), then the built-up area and its
//! settlements recomputed.

use super::blocks::{self, Blocks};
use super::context::Context;
use super::graph::{Class, Graph};
use super::lattice::Lattice;
use super::minor::{Grower, Growth, Nucleus};
use super::paths::{shortest, Found, TurnPenalty};
use super::roads;
use super::spaces::{Costs, InitialSpace, MajorSpace, NewSpace, Stitches};
use super::terrain::{Terrain, FORBIDDEN, LAND, WATER};
use super::traffic::{self, Pair, Route, Traffic};
use super::GrowError;
use crate::geometry::{dist, segment_intersection, P};
use rand::rngs::Xoshiro256PlusPlus;
use rand::{RngExt, SeedableRng};
use std::collections::{HashMap, HashSet};

/// Harbours whose land ends lie within this of a port's first harbour are that port (metres).
pub const PORT_SITE: f64 = 200.0;

/// A neighbouring city.
#[derive(Clone, Debug, PartialEq)]
pub struct City {
    /// Its lattice vertex (on the map's border).
    pub vertex: u32,
    /// Its position (metres).
    pub pos: P,
    /// Its node in the segment graph.
    pub node: u32,
    /// On water (trades by ship).
    pub water: bool,
}

/// The measures of one step (a row of `series.csv`).
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct StepStats {
    /// The step (0: the initial network).
    pub step: u32,
    /// Settlements (connected pieces of B of at least the smallest area).
    pub settlements: usize,
    /// |B| (hectares).
    pub built_up_ha: f64,
    /// Built-up blocks.
    pub blocks: usize,
    /// Minor-road length (km).
    pub minor_km: f64,
    /// Major-road length, bridges and harbours included (km).
    pub major_km: f64,
    /// Nuclei.
    pub nuclei: usize,
    /// Ports: harbour sites ([`Sim::port_sites`]: harbours within [`PORT_SITE`] of a site's first
    /// harbour are that site).
    pub ports: usize,
    /// Bridges built.
    pub bridges: usize,
    /// Trade routes.
    pub trade_routes: usize,
    /// Routes built or found this step.
    pub new_routes: usize,
    /// Traffic that found no capacity (sum over pairs).
    pub overflow: f64,
    /// Share of 4-way (or more) junctions among the junctions of the current pattern era's
    /// minor roads.
    pub four_way_share: f64,
    /// Orientation entropy (bits, 18 bins of 10°, length-weighted) of the era's minor roads.
    pub orientation_entropy: f64,
    /// Lane-kilometres of major road added in the step (new roads, minor roads made major, and
    /// widening).
    pub lane_km_added: f64,
    /// Lane-kilometres of major road (bridges and harbours included).
    pub lane_km: f64,
    /// Dead ends among the dead ends and junctions of the current pattern era's minor roads.
    pub dead_end_share: f64,
    /// The median area of the built-up blocks (m²).
    pub block_median_m2: f64,
}

/// A running simulation.
#[derive(Clone)]
pub struct Sim {
    /// The context.
    pub ctx: Context,
    /// The seed.
    pub seed: u64,
    /// The lattice graph 𝒢.
    pub lattice: Lattice,
    /// The road graph G.
    pub graph: Graph,
    /// Pairs and trade routes.
    pub traffic: Traffic,
    /// Neighbouring cities.
    pub cities: Vec<City>,
    /// Growth nuclei (the first is the centre).
    pub nuclei: Vec<Nucleus>,
    /// Blocks and the built-up area.
    pub blocks: Blocks,
    /// The current step.
    pub step: u32,
    /// μ.
    pub mu: f64,
    /// b.
    pub b: f64,
    /// One row per step so far.
    pub series: Vec<StepStats>,
    /// Bridges built (an existing road's bridges included).
    pub bridges: usize,
    /// The node of the centre the context names (`[center]`), which the initial network joins
    /// every neighbouring city to.
    pub centre: Option<u32>,
    rng: Xoshiro256PlusPlus,
    growth: Growth,
}

impl Sim {
    /// The initial network of a context (§3.2) with `seed` for every random choice: its existing
    /// roads, the neighbouring cities (at the ends of existing roads on the map's edge where
    /// they are near), the paths between them (through the centre when the context names one),
    /// the nuclei, and the pairs' first routes loaded.
    pub fn new(ctx: &Context, seed: u64) -> Result<Sim, GrowError> {
        Sim::with_terrain_seed(ctx, seed, seed)
    }

    /// [`Sim::new`] with the generated terrain drawn from `terrain_seed` (a gallery of initial
    /// networks on one terrain).
    pub fn with_terrain_seed(ctx: &Context, seed: u64, terrain_seed: u64) -> Result<Sim, GrowError> {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
        let terrain = Terrain::build(ctx, terrain_seed)?;
        roads::check_nuclei(ctx, &terrain)?;
        let centre_vertex = roads::centre_vertex(ctx, &terrain)?;
        let p = &ctx.params;
        let c = ctx.c(0);
        let lattice = Lattice::new(terrain, ctx.radius, p.slope_cut, p.o[0], p.bridge, c[2], c[4]);
        let mu = p.mu.unwrap_or_else(|| 0.5 + 0.4 * rng.random::<f64>());
        let b = p.b.unwrap_or_else(|| 0.7 + 0.6 * rng.random::<f64>());
        let vertices = place_cities(ctx, &lattice, &mut rng)?;
        let mut sim = Sim {
            ctx: ctx.clone(),
            seed,
            graph: Graph::new(ctx.size),
            traffic: Traffic { pairs: Vec::new(), routes: Vec::new(), per_lane: p.o[1] },
            cities: Vec::new(),
            nuclei: Vec::new(),
            blocks: Blocks::default(),
            step: 0,
            mu,
            b,
            series: Vec::new(),
            bridges: 0,
            centre: None,
            rng,
            growth: Growth::default(),
            lattice,
        };
        let given = roads::insert(&mut sim.graph, ctx, &sim.lattice.terrain, ctx.width(0))?;
        sim.bridges += given.bridges;
        let nl = sim.lattice.len() as u32;
        let centre = centre_vertex.map(|v| match roads::on_road(&sim.graph, ctx.center_position(), ctx.spacing) {
            Some((_, q)) => nl + sim.graph.node_at(q, true),
            None => v as u32,
        });
        let stitches = Stitches::new(&sim.graph, &sim.lattice, &Blocks::default(), p.stitch);
        let starts = sim.place_city_nodes(&vertices, &given.edge_ends);
        let (built, found) = pairs(ctx, &sim.cities, &mut sim.rng);
        sim.initial_network(&built, &found, &starts, centre, &stitches)?;
        sim.place_initial_nuclei();
        sim.blocks = sim.compute_blocks();
        let demand = sim.demand(0);
        for i in 0..sim.traffic.pairs.len() {
            sim.traffic.redistribute(&mut sim.graph, i, demand);
        }
        let row = sim.stats(built.len() + found.len());
        sim.series.push(row);
        Ok(sim)
    }

    /// The cities' nodes: an existing road's end on the map's edge within 2ℓ of the city's
    /// border vertex (each end taken once), else a node at the vertex. Returns each city's
    /// state in the initial network's search (its vertex, or lattice size + its node).
    fn place_city_nodes(&mut self, vertices: &[u32], edge_ends: &[u32]) -> Vec<u32> {
        let nl = self.lattice.len() as u32;
        let reach = 2.0 * self.ctx.spacing;
        let mut taken: Vec<u32> = Vec::new();
        let mut starts = Vec::with_capacity(vertices.len());
        for &v in vertices {
            let pos = self.lattice.pos(v);
            let water = self.lattice.class(v) == WATER;
            let end = edge_ends
                .iter()
                .copied()
                .filter(|n| !taken.contains(n) && dist(self.graph.nodes[*n as usize].pos, pos) <= reach)
                .min_by(|&a, &b| {
                    let d = |n: u32| dist(self.graph.nodes[n as usize].pos, pos);
                    d(a).total_cmp(&d(b)).then(a.cmp(&b))
                });
            let (node, start) = match end.filter(|_| !water) {
                Some(n) => {
                    taken.push(n);
                    (n, nl + n)
                }
                None => (self.graph.node_at(pos, !water), v),
            };
            self.graph.nodes[node as usize].spawned = true;
            let pos = self.graph.nodes[node as usize].pos;
            self.cities.push(City { vertex: v, pos, node, water });
            starts.push(start);
        }
        starts
    }

    /// t(t) = b · demand · G(t).
    pub fn demand(&self, t: u32) -> f64 {
        self.b * self.ctx.params.demand * self.ctx.growth(t)
    }

    fn compute_blocks(&self) -> Blocks {
        let p = &self.ctx.params;
        blocks::compute(&self.graph, &self.lattice.terrain, p.block_area, p.nb, p.settlement)
    }

    /// The initial network. With a centre (a search state), a path from every city (in random
    /// order) to it; then every pair's route is found in G. Without one, the roads of the pairs
    /// in `built` in order, then routes in G for the pairs in `found` (building them when G has
    /// none). Each path's lattice edges then weigh μ times as much; existing roads weigh μ
    /// times their length from the start (see [`InitialSpace`]).
    fn initial_network(
        &mut self,
        built: &[[usize; 2]],
        found: &[[usize; 2]],
        starts: &[u32],
        centre: Option<u32>,
        stitches: &Stitches,
    ) -> Result<(), GrowError> {
        let mut used: HashSet<(u32, u32)> = HashSet::new();
        let c = self.ctx.c(0);
        let h = [self.mu, 1.0, c[2], c[4]].into_iter().fold(f64::INFINITY, f64::min);
        if let Some(target) = centre {
            let mut order: Vec<usize> = (0..self.cities.len()).collect();
            for i in (1..order.len()).rev() {
                let j = self.rng.random_range(0..=i);
                order.swap(i, j);
            }
            for i in order {
                let Some(states) = self.initial_path(starts[i], target, h, &mut used, stitches) else {
                    return Err(GrowError::Unreachable { from: self.cities[i].pos, to: self.ctx.center_position() });
                };
                self.build_lattice_path(&states, 0);
            }
            let nl = self.lattice.len() as u32;
            self.centre =
                Some(if target >= nl { target - nl } else { self.graph.node_at(self.lattice.pos(target), true) });
        }
        for &pair in built.iter().chain(found) {
            let idx = self.traffic.pairs.len();
            self.traffic.pairs.push(Pair { cities: pair, routes: Vec::new(), overflow: 0.0 });
            let (u, v) = (self.cities[pair[0]].node, self.cities[pair[1]].node);
            if centre.is_some() || found.contains(&pair) {
                let costs = self.costs(c, 0.0);
                let none = HashMap::new();
                let mut space = MajorSpace { graph: &self.graph, blocks: &self.blocks, costs, used: &none };
                if let Some(f) = shortest(&mut space, u, v, 0.0, None) {
                    self.add_route(idx, f.states);
                    continue;
                }
            }
            let Some(states) = self.initial_path(starts[pair[0]], starts[pair[1]], h, &mut used, stitches) else {
                return Err(GrowError::Unreachable { from: self.cities[pair[0]].pos, to: self.cities[pair[1]].pos });
            };
            let chain = self.build_lattice_path(&states, 0);
            self.add_route(idx, chain);
        }
        Ok(())
    }

    /// The least-cost path of the initial network's graph between two states; its lattice edges
    /// are marked used.
    fn initial_path(
        &self,
        from: u32,
        to: u32,
        h: f64,
        used: &mut HashSet<(u32, u32)>,
        stitches: &Stitches,
    ) -> Option<Vec<u32>> {
        let mut space = InitialSpace {
            lattice: &self.lattice,
            graph: &self.graph,
            stitches,
            used,
            mu: self.mu,
            c: self.ctx.c(0),
            edges: Vec::new(),
            buf: Vec::new(),
        };
        let f = shortest(&mut space, from, to, h, None)?;
        let nl = self.lattice.len() as u32;
        for w in f.states.windows(2) {
            if w[0] < nl && w[1] < nl {
                used.insert((w[0].min(w[1]), w[0].max(w[1])));
            }
        }
        Some(f.states)
    }

    fn add_route(&mut self, pair: usize, nodes: Vec<u32>) {
        let r = self.traffic.routes.len();
        self.traffic.routes.push(Route { pair, nodes, traffic: 0.0, born: self.step });
        self.traffic.pairs[pair].routes.push(r);
    }

    /// Inserts a path of 𝒢′ states (lattice vertices below the lattice size, nodes above) as
    /// segments; returns its node chain. Splits are applied to every route.
    fn build_lattice_path(&mut self, states: &[u32], width_step: u32) -> Vec<u32> {
        let nl = self.lattice.len() as u32;
        let width = self.ctx.width(width_step);
        let mark = self.graph.splits.len();
        let mut chain: Vec<u32> = Vec::new();
        let mut prev_node: Option<u32> = None;
        let mut prev_state: Option<u32> = None;
        for &s in states {
            let node = if s >= nl {
                s - nl
            } else {
                let water = self.lattice.class(s) == WATER;
                self.graph.node_at(self.lattice.pos(s), !water)
            };
            if let (Some(pn), Some(ps)) = (prev_node, prev_state) {
                let class = self.class_between(ps, s, pn, node);
                if class == Class::Bridge && self.graph.find(pn, node).is_none() {
                    self.bridges += 1;
                }
                let w = match class {
                    Class::Minor => 1.0,
                    Class::Water => 1.0,
                    Class::Major => {
                        let existing = self.graph.find(pn, node).map(|e| self.graph.segs[e as usize].class);
                        let ext = self
                            .graph
                            .find(pn, node)
                            .map(|e| self.blocks.extendible.get(e as usize).copied().unwrap_or(true))
                            .unwrap_or(true);
                        if existing == Some(Class::Minor) && !ext {
                            1.0
                        } else if existing.is_some() && !ext {
                            0.0
                        } else {
                            width
                        }
                    }
                    _ => width,
                };
                let piece = self.graph.insert(pn, node, class, w, self.step);
                for n in piece {
                    if chain.last() != Some(&n) {
                        chain.push(n);
                    }
                }
            } else {
                chain.push(node);
            }
            prev_node = Some(node);
            prev_state = Some(s);
        }
        apply_splits(&mut chain, &self.graph.splits[mark..]);
        self.traffic.apply_splits(&self.graph, mark);
        remove_loops(&mut chain);
        chain
    }

    /// The class of the segment(s) between two consecutive states.
    fn class_between(&self, a: u32, b: u32, na: u32, nb: u32) -> Class {
        let nl = self.lattice.len() as u32;
        if a >= nl && b >= nl {
            return match self.graph.find(na, nb).map(|s| self.graph.segs[s as usize].class) {
                Some(c @ (Class::Bridge | Class::Harbour | Class::Water)) => c,
                _ => Class::Major,
            };
        }
        let class = |s: u32, n: u32| {
            if s < nl {
                self.lattice.class(s)
            } else {
                self.lattice.terrain.class_at(self.graph.nodes[n as usize].pos)
            }
        };
        match (class(a, na), class(b, nb)) {
            (WATER, WATER) => Class::Water,
            (LAND, LAND) => {
                let (p, q) = (self.graph.nodes[na as usize].pos, self.graph.nodes[nb as usize].pos);
                let t = &self.lattice.terrain;
                let k = (dist(p, q) / (t.spacing / 2.0)).ceil().max(1.0) as usize;
                let wet = (1..k).any(|i| {
                    let f = i as f64 / k as f64;
                    t.class_at([p[0] + (q[0] - p[0]) * f, p[1] + (q[1] - p[1]) * f]) == WATER
                });
                if wet {
                    Class::Bridge
                } else {
                    Class::Major
                }
            }
            _ => Class::Harbour,
        }
    }

    /// Nuclei at junctions of more than two trade roads and at the land ends of bridges and
    /// harbours; the centre nucleus is at the named centre, else the one nearest the map's
    /// centre. Then the context's nuclei from step 0.
    fn place_initial_nuclei(&mut self) {
        let mut found: Vec<(u32, usize)> = Vec::new();
        for n in 0..self.graph.nodes.len() as u32 {
            let deg = self.trade_degree(n);
            let special = self.graph.adj[n as usize]
                .iter()
                .any(|&s| matches!(self.graph.segs[s as usize].class, Class::Bridge | Class::Harbour));
            if (deg > 2 || special) && self.lattice.terrain.class_at(self.graph.nodes[n as usize].pos) == LAND {
                found.push((n, deg));
            }
        }
        let max_deg = found.iter().map(|f| f.1).max().unwrap_or(1).max(1) as f64;
        for (n, deg) in found {
            let pos = self.graph.nodes[n as usize].pos;
            let strength = 0.9 * deg as f64 / max_deg * self.attenuation(pos);
            self.add_nucleus(pos, strength);
        }
        let strength = self.ctx.params.center_strength;
        if let Some(n) = self.centre {
            let pos = self.graph.nodes[n as usize].pos;
            let near = 2.0 * self.ctx.spacing;
            self.nuclei.retain(|q| dist(q.pos, pos) >= near);
            self.nuclei.insert(0, Nucleus { pos, strength, born: 0 });
        } else {
            self.place_centre_nucleus(strength);
        }
        self.add_context_nuclei(0);
    }

    /// Road segments other than minor roads at a node.
    fn trade_degree(&self, n: u32) -> usize {
        self.graph.adj[n as usize]
            .iter()
            .filter(|&&s| {
                let c = self.graph.segs[s as usize].class;
                c.is_road() && c.is_trade()
            })
            .count()
    }

    /// Without a named centre: the nucleus nearest the map's centre is q_c (a road node there
    /// when there is no nucleus).
    fn place_centre_nucleus(&mut self, strength: f64) {
        let c = self.ctx.center_position();
        let centre = match self.nuclei.iter().enumerate().min_by(|a, b| dist(a.1.pos, c).total_cmp(&dist(b.1.pos, c))) {
            Some((i, _)) => i,
            None => {
                let n = (0..self.graph.nodes.len())
                    .filter(|&n| {
                        self.graph.road_degree(n as u32) > 0
                            && self.lattice.terrain.class_at(self.graph.nodes[n].pos) == LAND
                    })
                    .min_by(|&a, &b| dist(self.graph.nodes[a].pos, c).total_cmp(&dist(self.graph.nodes[b].pos, c)));
                let pos = n.map(|n| self.graph.nodes[n].pos).unwrap_or(c);
                self.nuclei.push(Nucleus { pos, strength: 0.0, born: 0 });
                self.nuclei.len() - 1
            }
        };
        let mut q = self.nuclei.remove(centre);
        q.strength = strength;
        self.nuclei.insert(0, q);
    }

    /// The context's `[[nucleus]]` entries whose `from` is step `t`, as given.
    fn add_context_nuclei(&mut self, t: u32) {
        for n in self.ctx.nucleus.iter().filter(|n| n.from == t) {
            self.nuclei.push(Nucleus { pos: n.position, strength: n.strength, born: t });
        }
    }

    fn add_nucleus(&mut self, pos: P, strength: f64) -> bool {
        if self.nuclei.iter().any(|q| dist(q.pos, pos) < 2.0 * self.ctx.spacing) {
            return false;
        }
        self.nuclei.push(Nucleus { pos, strength: strength.clamp(0.01, 0.99), born: self.step });
        true
    }

    /// Nuclei weaken towards the map's border.
    fn attenuation(&self, p: P) -> f64 {
        let [w, h] = self.ctx.size;
        let d = p[0].min(p[1]).min(w - p[0]).min(h - p[1]).max(0.0);
        let x = (d / (0.2 * w.min(h))).min(1.0);
        x * x * (3.0 - 2.0 * x)
    }

    /// One time step (Alg. 1): minor roads, then traffic and major roads per pair (Alg. 2),
    /// then the built-up area.
    pub fn step(&mut self) {
        self.step += 1;
        let t = self.step;
        self.add_context_nuclei(t);
        let c = self.ctx.c(t);
        (self.lattice.harbour_factor, self.lattice.bridge_factor) = (c[2], c[4]);
        let count = self.ctx.growth(t).round() as usize;
        let mark = self.graph.splits.len();
        {
            let pattern = self.ctx.pattern(t).clone();
            let mut g = Grower {
                graph: &mut self.graph,
                terrain: &self.lattice.terrain,
                nuclei: &self.nuclei,
                pattern: &pattern,
                slope_cut: self.ctx.params.slope_cut,
                step: t,
                rng: &mut self.rng,
                growth: &mut self.growth,
            };
            g.grow(count);
        }
        self.traffic.apply_splits(&self.graph, mark);
        self.blocks = self.compute_blocks();
        let mut stitches = Stitches::new(&self.graph, &self.lattice, &self.blocks, self.ctx.params.stitch);
        let demand = self.demand(t);
        let mut new_routes = 0;
        for i in 0..self.traffic.pairs.len() {
            self.traffic.clear_pair(&mut self.graph, i);
            let avail = self.traffic.available_list(&self.graph, i);
            if avail < demand && self.propose(i, demand - avail, &mut stitches) {
                new_routes += 1;
            }
            self.traffic.redistribute(&mut self.graph, i, demand);
        }
        self.blocks = self.compute_blocks();
        let row = self.stats(new_routes);
        self.series.push(row);
    }

    /// PROPOSEFROMMAJOR and PROPOSEFROMNEW for a pair short of `delta`; the winner (least
    /// O₃ · LENGTH + O₄ · COST) becomes a new trade route. Returns whether one was added.
    fn propose(&mut self, pair: usize, delta: f64, stitches: &mut Stitches) -> bool {
        let costs = self.costs(self.ctx.c(self.step), delta);
        let p = &self.ctx.params;
        let [sc, sw, sh] = self.ctx.turn(self.step);
        let penalty = TurnPenalty::new(sc.to_radians(), sw.to_radians(), sh);
        let turn = move |c: f64| penalty.at_cos(c);
        let [a, b] = self.traffic.pairs[pair].cities;
        let (u, v) = (self.cities[a].node, self.cities[b].node);
        let nl = self.lattice.len() as u32;
        let h = costs.min_factor();
        let used = self.traffic.saturation(&self.graph, pair);
        let major = {
            let mut space = MajorSpace { graph: &self.graph, blocks: &self.blocks, costs, used: &used };
            shortest(&mut space, u, v, h, Some(&turn))
        };
        let new = {
            let mut space = NewSpace {
                lattice: &self.lattice,
                graph: &self.graph,
                blocks: &self.blocks,
                stitches,
                costs,
                used: &used,
                edges: Vec::new(),
                buf: Vec::new(),
            };
            shortest(&mut space, nl + u, nl + v, h, Some(&turn))
        };
        let score = |f: &Found, states_are_nodes: bool| {
            let pts: Vec<P> = f
                .states
                .iter()
                .map(|&s| {
                    if states_are_nodes {
                        self.graph.nodes[s as usize].pos
                    } else if s >= nl {
                        self.graph.nodes[(s - nl) as usize].pos
                    } else {
                        self.lattice.pos(s)
                    }
                })
                .collect();
            let len: f64 = pts.windows(2).map(|w| dist(w[0], w[1])).sum();
            p.o[2] * len + p.o[3] * f.cost
        };
        let existing: Vec<Vec<u32>> =
            self.traffic.pairs[pair].routes.iter().map(|&r| self.traffic.routes[r].nodes.clone()).collect();
        let use_major = match (&major, &new) {
            (Some(m), Some(n)) => score(m, true) <= score(n, false),
            (Some(_), None) => true,
            (None, Some(_)) => false,
            (None, None) => return false,
        };
        let chain = if use_major {
            let m = major.expect("chosen");
            if existing.contains(&m.states) {
                return false;
            }
            m.states
        } else {
            let n = new.expect("chosen");
            let before_nodes = self.graph.nodes.len();
            let chain = self.build_lattice_path(&n.states, self.step);
            self.widen(&chain, delta, &used);
            self.new_nuclei(&chain, before_nodes);
            stitches.extend(&self.graph, &self.lattice, &self.blocks);
            chain
        };
        if chain.len() < 2
            || existing.contains(&chain)
            || !chain.windows(2).all(|w| self.graph.find(w[0], w[1]).is_some())
        {
            return false;
        }
        self.add_route(pair, chain);
        true
    }

    /// The segment weights of the proposal graphs at coefficients `c` for a shortfall `delta`.
    fn costs(&self, c: [f64; 6], delta: f64) -> Costs {
        Costs { c, per_lane: self.traffic.per_lane, max_lanes: self.ctx.params.max_lanes, delta }
    }

    /// Widens a new route's extendible pieces (F16) and makes reused minor roads major: each to
    /// at least A(t) lanes, and one without room for the shortfall `delta` beside its traffic
    /// and what the pair's own routes take on it (`used`) to one lane more, or to as many as
    /// they need, at most `max_lanes` (capacity follows lanes: O₂ per lane). Non-extendible reused minor roads get one lane; fixed roads are kept as
    /// they are.
    fn widen(&mut self, chain: &[u32], delta: f64, used: &HashMap<u32, f64>) {
        let a = self.ctx.width(self.step);
        let per = self.traffic.per_lane;
        let max = self.ctx.params.max_lanes;
        for s in traffic::segments(&self.graph, chain) {
            let ext = self.blocks.extendible.get(s as usize).copied().unwrap_or(true);
            let g = &mut self.graph.segs[s as usize];
            if g.fixed || !matches!(g.class, Class::Minor | Class::Major) {
                continue;
            }
            let load = g.load + used.get(&s).copied().unwrap_or(0.0);
            let lanes = if ext {
                let mut w = g.width.max(a);
                if per * w - load < delta {
                    w = w.max(g.width + 1.0).max(((load + delta) / per).ceil());
                }
                w.min(max.max(g.width))
            } else {
                g.width.max(1.0)
            };
            if g.class == Class::Minor {
                g.class = Class::Major;
                g.width = lanes;
            } else if ext {
                g.width = lanes;
            }
        }
    }

    /// Nuclei at the new route's junctions with other major roads and its bridge and harbour
    /// ends, each with one more at a random road node nearby ("to account for chance").
    fn new_nuclei(&mut self, chain: &[u32], _before: usize) {
        for &n in chain {
            let pos = self.graph.nodes[n as usize].pos;
            if self.lattice.terrain.class_at(pos) != LAND || self.cities.iter().any(|c| c.node == n) {
                continue;
            }
            let trade = self.graph.adj[n as usize].iter().filter(|&&s| {
                let c = self.graph.segs[s as usize].class;
                c.is_road() && c.is_trade()
            });
            let special = self.graph.adj[n as usize]
                .iter()
                .any(|&s| matches!(self.graph.segs[s as usize].class, Class::Bridge | Class::Harbour));
            if trade.count() < 3 && !special {
                continue;
            }
            let strength = (0.3 + 0.5 * self.rng.random::<f64>()) * self.attenuation(pos);
            if self.add_nucleus(pos, strength) {
                let near: Vec<u32> = self
                    .graph
                    .nodes_near(pos, 500.0)
                    .into_iter()
                    .filter(|&m| {
                        self.graph.road_degree(m) > 0
                            && self.lattice.terrain.class_at(self.graph.nodes[m as usize].pos) == LAND
                    })
                    .collect();
                if !near.is_empty() {
                    let m = near[self.rng.random_range(0..near.len())];
                    let q = self.graph.nodes[m as usize].pos;
                    let s = (0.1 + 0.4 * self.rng.random::<f64>()) * self.attenuation(q);
                    self.add_nucleus(q, s);
                }
            }
        }
    }

    /// The measures of the current state.
    pub fn stats(&self, new_routes: usize) -> StepStats {
        let mut minor = 0.0;
        let mut major = 0.0;
        let mut harbours = Vec::new();
        let mut lanes = 0.0;
        for (s, g) in self.graph.segs.iter().enumerate() {
            let l = self.graph.length(s as u32);
            match g.class {
                Class::Minor => minor += l,
                Class::Major | Class::Bridge => major += l,
                Class::Harbour => {
                    major += l;
                    harbours.push(s as u32);
                }
                Class::Water => {}
            }
            if g.class.is_road() && g.class.is_trade() {
                lanes += g.width * l;
            }
        }
        let era = self.ctx.pattern(self.step).from;
        let (four, entropy, dead_ends) = era_measures(&self.graph, era);
        let mut areas: Vec<f64> = self.blocks.faces.iter().filter(|f| f.built_up).map(|f| f.area).collect();
        areas.sort_by(f64::total_cmp);
        let median = if areas.is_empty() { 0.0 } else { areas[areas.len() / 2] };
        StepStats {
            step: self.step,
            settlements: self.blocks.settlements.len(),
            built_up_ha: round(self.blocks.built_area / 10_000.0, 2),
            blocks: self.blocks.block_count(),
            minor_km: round(minor / 1000.0, 3),
            major_km: round(major / 1000.0, 3),
            nuclei: self.nuclei.len(),
            ports: self.port_sites(&harbours).len(),
            bridges: self.bridges,
            trade_routes: self.traffic.routes.len(),
            new_routes,
            overflow: round(self.traffic.pairs.iter().map(|p| p.overflow).sum(), 3),
            four_way_share: round(four, 4),
            orientation_entropy: round(entropy, 4),
            lane_km_added: round((lanes / 1000.0 - self.series.last().map_or(0.0, |r| r.lane_km)).max(0.0), 3),
            lane_km: round(lanes / 1000.0, 3),
            dead_end_share: round(dead_ends, 4),
            block_median_m2: round(median, 0),
        }
    }

    /// The harbour sites: the land ends of the harbour segments `harbours`, in order, each
    /// joining the first site whose first harbour is within [`PORT_SITE`] of it, or founding a
    /// new one (so a site stays where it was founded as harbours are added); each site's first
    /// land end.
    pub fn port_sites(&self, harbours: &[u32]) -> Vec<P> {
        let mut sites: Vec<P> = Vec::new();
        for &s in harbours {
            let (a, b) = self.graph.ends(s);
            let end = if self.lattice.terrain.class_at(a) == LAND { a } else { b };
            if sites.iter().all(|&q| dist(q, end) > PORT_SITE) {
                sites.push(end);
            }
        }
        sites
    }

    /// Road segments that cross, or a node lying inside another segment: the planarity check the
    /// graph keeps (kept for diagnostics; tests use their own).
    pub fn crossings(&self) -> usize {
        let mut n = 0;
        for (i, g) in self.graph.segs.iter().enumerate() {
            if !g.class.is_road() {
                continue;
            }
            let (a, b) = self.graph.ends(i as u32);
            for j in self.graph.segs_near([(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0], dist(a, b) / 2.0 + 1.0) {
                let h = &self.graph.segs[j];
                if j <= i || !h.class.is_road() || h.a == g.a || h.a == g.b || h.b == g.a || h.b == g.b {
                    continue;
                }
                let (c, d) = self.graph.ends(j as u32);
                if segment_intersection(a, b, c, d).is_some() {
                    n += 1;
                }
            }
        }
        n
    }
}

fn round(x: f64, digits: i32) -> f64 {
    let f = 10f64.powi(digits);
    (x * f).round() / f
}

/// Applies splits `(a, b, x)` to a node path.
fn apply_splits(nodes: &mut Vec<u32>, splits: &[(u32, u32, u32)]) {
    for &(a, b, x) in splits {
        let mut i = 0;
        while i + 1 < nodes.len() {
            let (u, v) = (nodes[i], nodes[i + 1]);
            if (u, v) == (a, b) || (u, v) == (b, a) {
                nodes.insert(i + 1, x);
                i += 1;
            }
            i += 1;
        }
    }
}

/// Cuts the loops out of a node path (a node visited twice keeps its first visit).
fn remove_loops(nodes: &mut Vec<u32>) {
    let mut out: Vec<u32> = Vec::with_capacity(nodes.len());
    for &n in nodes.iter() {
        if let Some(i) = out.iter().position(|&m| m == n) {
            out.truncate(i + 1);
        } else {
            out.push(n);
        }
    }
    *nodes = out;
}

/// The 4-way share, orientation entropy and dead-end share of the minor roads built since step
/// `from`.
fn era_measures(graph: &Graph, from: u32) -> (f64, f64, f64) {
    let mut segments = Vec::new();
    let mut nodes = HashSet::new();
    for (s, g) in graph.segs.iter().enumerate() {
        if g.class != Class::Minor || g.born < from.max(1) {
            continue;
        }
        segments.push(graph.ends(s as u32));
        nodes.insert(g.a);
        nodes.insert(g.b);
    }
    let entropy = crate::stats::orientation::axial_entropy_bits(segments, 18);
    let (mut junctions, mut four, mut ends) = (0, 0, 0);
    for n in nodes {
        let d = graph.road_degree(n);
        ends += (d == 1) as usize;
        if d >= 3 {
            junctions += 1;
            if d >= 4 {
                four += 1;
            }
        }
    }
    let share = |k: usize, of: usize| if of > 0 { k as f64 / of as f64 } else { 0.0 };
    (share(four, junctions), entropy, share(ends, ends + junctions))
}

/// The neighbouring cities' border vertices: the context's positions, or `neighbours` (or
/// 4 + Binomial(6, ½)) rays from the centre at 2πi/c + θ + θᵢ (§3.5), each moved along the
/// border to the nearest vertex that is not forbidden and not taken.
fn place_cities(ctx: &Context, lattice: &Lattice, rng: &mut Xoshiro256PlusPlus) -> Result<Vec<u32>, GrowError> {
    let [w, h] = ctx.size;
    let targets: Vec<P> = if !ctx.neighbour.is_empty() {
        ctx.neighbour.iter().map(|n| n.position).collect()
    } else {
        let c = ctx.neighbours.unwrap_or_else(|| 4 + (0..6).filter(|_| rng.random::<bool>()).count() as u32) as usize;
        let x = ctx.center_position();
        let theta = rng.random::<f64>() * std::f64::consts::TAU;
        (0..c)
            .map(|i| {
                let jitter = (2.0 * rng.random::<f64>() - 1.0) * std::f64::consts::PI / (2.0 * c as f64);
                let a = std::f64::consts::TAU * i as f64 / c as f64 + theta + jitter;
                let d = [a.cos(), a.sin()];
                // Where the ray leaves the map.
                let tx = if d[0] > 1e-12 {
                    (w - x[0]) / d[0]
                } else if d[0] < -1e-12 {
                    -x[0] / d[0]
                } else {
                    f64::INFINITY
                };
                let ty = if d[1] > 1e-12 {
                    (h - x[1]) / d[1]
                } else if d[1] < -1e-12 {
                    -x[1] / d[1]
                } else {
                    f64::INFINITY
                };
                let t = tx.min(ty);
                [(x[0] + d[0] * t).clamp(0.0, w), (x[1] + d[1] * t).clamp(0.0, h)]
            })
            .collect()
    };
    let t = &lattice.terrain;
    let border: Vec<u32> = (0..lattice.len() as u32)
        .filter(|&v| {
            let (x, y) = (v as usize % t.nx, v as usize / t.nx);
            x == 0 || y == 0 || x + 1 == t.nx || y + 1 == t.ny
        })
        .collect();
    let mut taken: Vec<u32> = Vec::new();
    for (i, p) in targets.iter().enumerate() {
        let best = border
            .iter()
            .copied()
            .filter(|&v| lattice.class(v) != FORBIDDEN && !taken.contains(&v))
            .min_by(|&a, &b| dist(lattice.pos(a), *p).total_cmp(&dist(lattice.pos(b), *p)).then(a.cmp(&b)));
        match best {
            Some(v) => taken.push(v),
            None => {
                return Err(GrowError::Field {
                    path: Default::default(),
                    field: format!("neighbour[{i}]"),
                    message: "no free border vertex is left for this city".into(),
                })
            }
        }
    }
    Ok(taken)
}

/// The pair lists: all pairs sorted by the angle they span at the centre, the smallest removed
/// while the initial road network stays connected (stopping at the first that would disconnect
/// it, [`roads_connected`]); the rest permuted is γ′ (built), and each removed pair is added back
/// to γ′ at a random place with probability `add_back` (§3.5's variation) or only found in G.
fn pairs(ctx: &Context, cities: &[City], rng: &mut Xoshiro256PlusPlus) -> (Vec<[usize; 2]>, Vec<[usize; 2]>) {
    let x = ctx.center_position();
    let mut all: Vec<(f64, [usize; 2])> = Vec::new();
    for i in 0..cities.len() {
        for j in i + 1..cities.len() {
            let ang = super::paths::angle(cities[i].pos, x, cities[j].pos);
            all.push((ang, [i, j]));
        }
    }
    all.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let pos: Vec<P> = cities.iter().map(|c| c.pos).collect();
    let mut keep: Vec<[usize; 2]> = all.iter().map(|a| a.1).collect();
    let mut removed = Vec::new();
    while let Some(&cand) = keep.first() {
        let rest: Vec<[usize; 2]> = keep[1..].to_vec();
        if !roads_connected(&pos, &rest) {
            break;
        }
        removed.push(cand);
        keep = rest;
    }
    for i in (1..keep.len()).rev() {
        let j = rng.random_range(0..=i);
        keep.swap(i, j);
    }
    let mut found = Vec::new();
    for pair in removed {
        if rng.random::<f64>() < ctx.params.add_back {
            let at = rng.random_range(0..=keep.len());
            keep.insert(at, pair);
        } else {
            found.push(pair);
        }
    }
    (keep, found)
}

/// Whether the roads of `pairs`, taken as straight lines between their cities at `pos`, make
/// one connected network reaching every city: two roads are joined where they share a city or
/// cross (the initial network's junctions), before any road is built.
pub fn roads_connected(pos: &[P], pairs: &[[usize; 2]]) -> bool {
    let n = pairs.len();
    let mut covered = vec![false; pos.len()];
    for p in pairs {
        covered[p[0]] = true;
        covered[p[1]] = true;
    }
    if n == 0 || covered.iter().any(|c| !c) {
        return false;
    }
    let mut joins: Vec<[usize; 2]> = Vec::new();
    for i in 0..n {
        for j in i + 1..n {
            let (a, b) = (pairs[i], pairs[j]);
            let share = a.iter().any(|c| b.contains(c));
            if share || segment_intersection(pos[a[0]], pos[a[1]], pos[b[0]], pos[b[1]]).is_some() {
                joins.push([i, j]);
            }
        }
    }
    connected(n, &joins)
}

fn connected(n: usize, edges: &[[usize; 2]]) -> bool {
    let mut parent: Vec<usize> = (0..n).collect();
    fn find(p: &mut [usize], x: usize) -> usize {
        let mut r = x;
        while p[r] != r {
            r = p[r];
        }
        let mut y = x;
        while p[y] != r {
            let next = p[y];
            p[y] = r;
            y = next;
        }
        r
    }
    for e in edges {
        let (a, b) = (find(&mut parent, e[0]), find(&mut parent, e[1]));
        parent[a] = b;
    }
    let root = find(&mut parent, 0);
    (0..n).all(|i| find(&mut parent, i) == root)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crossing_roads_join_the_initial_network() {
        let corners = [[0.0, 0.0], [100.0, 0.0], [100.0, 100.0], [0.0, 100.0]];
        assert!(roads_connected(&corners, &[[0, 2], [1, 3]]), "the diagonals cross");
        assert!(!roads_connected(&corners, &[[0, 1], [2, 3]]), "two opposite sides do not meet");
        assert!(!roads_connected(&corners, &[[0, 2]]), "cities 1 and 3 are on no road");
        assert!(roads_connected(&corners, &[[0, 1], [1, 2], [2, 3]]));
    }
}
