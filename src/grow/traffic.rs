//! Trade between city pairs (§3.4.2, Alg. 2): each pair's trade routes (paths of trade
//! segments: major roads, bridges, harbours, waterways), their traffic T(P), segment traffic
//! T(s) = Σ T(P), available capacities T_A(s) = O₂ · WIDTH(s) − T(s), T_A(P) = min T_A(s), the
//! available capacity of a route list T_A(𝒫) (routes saturated one by one, shortest first), and
//! the greedy redistribution of a pair's demand (what does not fit goes on the shortest route
//! and is recorded as overflow).

use super::graph::{Class, Graph};
use std::collections::HashMap;

/// A pair of neighbouring cities.
#[derive(Clone, Debug, PartialEq)]
pub struct Pair {
    /// The cities (indices).
    pub cities: [usize; 2],
    /// Its trade routes (indices into [`Traffic::routes`]).
    pub routes: Vec<usize>,
    /// Demand that found no capacity in the last step.
    pub overflow: f64,
}

/// A trade route.
#[derive(Clone, Debug, PartialEq)]
pub struct Route {
    /// Its pair.
    pub pair: usize,
    /// Its nodes, from the pair's first city to its second.
    pub nodes: Vec<u32>,
    /// Its traffic T(P).
    pub traffic: f64,
    /// The step it was added in.
    pub born: u32,
}

/// Pairs and routes.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Traffic {
    /// City pairs, in the order Alg. 2 visits them.
    pub pairs: Vec<Pair>,
    /// Trade routes.
    pub routes: Vec<Route>,
    /// O₂: traffic per lane.
    pub per_lane: f64,
}

/// A segment's capacity O₂ · WIDTH (waterways unlimited).
pub fn capacity(graph: &Graph, s: u32, per_lane: f64) -> f64 {
    let g = &graph.segs[s as usize];
    if g.class == Class::Water {
        f64::INFINITY
    } else {
        per_lane * g.width
    }
}

/// The segments of a node path (each consecutive pair must be joined).
pub fn segments(graph: &Graph, nodes: &[u32]) -> Vec<u32> {
    nodes.windows(2).map(|w| graph.find(w[0], w[1]).expect("a route runs along segments")).collect()
}

/// A node path's length (metres).
pub fn length(graph: &Graph, nodes: &[u32]) -> f64 {
    nodes
        .windows(2)
        .map(|w| crate::geometry::dist(graph.nodes[w[0] as usize].pos, graph.nodes[w[1] as usize].pos))
        .sum()
}

impl Traffic {
    /// Applies the graph's splits from `from` on to every route (a split segment's traffic
    /// is already on both pieces).
    pub fn apply_splits(&mut self, graph: &Graph, from: usize) {
        for &(a, b, x) in &graph.splits[from..] {
            for r in &mut self.routes {
                let mut i = 0;
                while i + 1 < r.nodes.len() {
                    let (u, v) = (r.nodes[i], r.nodes[i + 1]);
                    if (u, v) == (a, b) || (u, v) == (b, a) {
                        r.nodes.insert(i + 1, x);
                        i += 1;
                    }
                    i += 1;
                }
            }
        }
    }

    /// Adds `amount` to route `r` and its segments.
    pub fn add(&mut self, graph: &mut Graph, r: usize, amount: f64) {
        self.routes[r].traffic += amount;
        for s in segments(graph, &self.routes[r].nodes) {
            graph.segs[s as usize].load += amount;
        }
    }

    /// T_A(P) with extra loads `extra` on some segments.
    fn available(&self, graph: &Graph, r: usize, extra: &HashMap<u32, f64>) -> f64 {
        segments(graph, &self.routes[r].nodes)
            .into_iter()
            .map(|s| {
                capacity(graph, s, self.per_lane) - graph.segs[s as usize].load - extra.get(&s).copied().unwrap_or(0.0)
            })
            .fold(f64::INFINITY, f64::min)
            .max(0.0)
    }

    /// A pair's routes, shortest first (ties by index).
    pub fn by_length(&self, graph: &Graph, pair: usize) -> Vec<usize> {
        let mut rs: Vec<(f64, usize)> =
            self.pairs[pair].routes.iter().map(|&r| (length(graph, &self.routes[r].nodes), r)).collect();
        rs.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        rs.into_iter().map(|x| x.1).collect()
    }

    /// T_A(𝒫) of a pair: its routes saturated one by one, shortest first, the traffic this took
    /// summed (nothing is changed).
    pub fn available_list(&self, graph: &Graph, pair: usize) -> f64 {
        self.saturate(graph, pair).0
    }

    /// The traffic a pair's routes take on each segment when saturated one by one, shortest
    /// first (as [`Traffic::available_list`] counts them): what a new route of the pair finds
    /// already used beside the other pairs' traffic.
    pub fn saturation(&self, graph: &Graph, pair: usize) -> HashMap<u32, f64> {
        self.saturate(graph, pair).1
    }

    fn saturate(&self, graph: &Graph, pair: usize) -> (f64, HashMap<u32, f64>) {
        let mut extra: HashMap<u32, f64> = HashMap::new();
        let mut total = 0.0;
        for r in self.by_length(graph, pair) {
            let a = self.available(graph, r, &extra);
            if a.is_infinite() {
                return (f64::INFINITY, extra);
            }
            total += a;
            for s in segments(graph, &self.routes[r].nodes) {
                *extra.entry(s).or_insert(0.0) += a;
            }
        }
        (total, extra)
    }

    /// Removes a pair's traffic from its routes and segments.
    pub fn clear_pair(&mut self, graph: &mut Graph, pair: usize) {
        for r in self.pairs[pair].routes.clone() {
            let t = self.routes[r].traffic;
            self.add(graph, r, -t);
            self.routes[r].traffic = 0.0;
        }
    }

    /// Puts `demand` on a pair's routes greedily, shortest first; the rest goes on the shortest
    /// and is returned (the overflow).
    pub fn redistribute(&mut self, graph: &mut Graph, pair: usize, demand: f64) -> f64 {
        let order = self.by_length(graph, pair);
        let mut left = demand;
        for &r in &order {
            if left <= 0.0 {
                break;
            }
            let a = self.available(graph, r, &HashMap::new()).min(left);
            if a > 0.0 {
                self.add(graph, r, a);
                left -= a;
            }
        }
        let overflow = if left > 1e-9 { left } else { 0.0 };
        if overflow > 0.0 {
            if let Some(&r) = order.first() {
                self.add(graph, r, overflow);
            }
        }
        self.pairs[pair].overflow = overflow;
        overflow
    }
}
