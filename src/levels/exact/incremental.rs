//! An incremental exact layout for levels too large for one model: the nodes in steps of a few
//! (the annealer's chains, cut into pieces and packed up to [`PIECE`] nodes), each step one
//! model over its new nodes only. Every earlier node within reach of the step is in that model
//! with its block and position held constant (a door partner for its edges into the step and a
//! block the step must not overlap); earlier nodes out of reach (by the position bounds: hop
//! distance × the longest contact offset) are left out. When a step has no layout, it is merged
//! with the step before and the two are solved again (up to [`MERGE_CAP`] nodes), else the step
//! before is solved again with a no-good cut on its contacts (at most [`RETRIES`] times). A
//! failure of the first step, with nothing placed, proves the level infeasible (its nodes induce
//! a subgraph without a layout). The layout is checked by the validator like the whole model's.

use super::super::anneal;
use super::super::cspace::CSpaces;
use super::super::milp::{self, LevelModel, Part};
use super::super::spec::{BlockId, EdgeId, Level, NodeId};
use super::super::{Layout, Placement};
use super::{checked, conflict, solve_gap, solve_once, Answer, Clock, ExactOptions, ExactReport, LevelError};
use crate::explain::Verdict;
use crate::geometry::P;
use serde::Serialize;
use std::collections::{BTreeSet, VecDeque};

/// Nodes per step at most (chains are cut into pieces of at most this many and small ones are
/// packed together up to it), for nodes of one allowed block; see [`piece`].
pub const PIECE: usize = 8;

/// Allowed blocks summed over a step's nodes, at most: nodes of many blocks make smaller steps.
const PIECE_BLOCKS: usize = 16;

/// A failed step is merged with the one before while the two have at most this many times
/// [`piece`] nodes.
pub const MERGE_FACTOR: usize = 3;

/// Nodes per step for this level: [`PIECE`], fewer when the nodes allow several blocks (at
/// most [`PIECE_BLOCKS`] allowed blocks over a step on average), at least 2.
pub fn piece(level: &Level) -> usize {
    let blocks: usize = level.nodes.iter().map(|n| n.blocks.len()).sum();
    let mean = blocks as f64 / level.nodes.len().max(1) as f64;
    ((PIECE_BLOCKS as f64 / mean).floor() as usize).clamp(2, PIECE)
}

/// No-good re-solves of one step at most, once merging is out.
pub const RETRIES: usize = 8;

/// Relative gap at which a step's solve stops pushing its nodes outward.
const PUSH_GAP: f64 = 0.25;

/// Seconds one step's solve may take at most.
const STEP_LIMIT: f64 = 20.0;

/// What the incremental layout did.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Stats {
    /// Steps planned (after packing).
    pub steps: usize,
    /// Step solves made.
    pub solves: usize,
    /// Failed steps merged with the one before.
    pub merges: usize,
    /// Steps solved again with a no-good cut.
    pub retries: usize,
    /// New nodes of the largest step solved.
    pub largest_step: usize,
    /// Placed nodes held fixed in one step's model, at most.
    pub most_fixed: usize,
    /// Seconds.
    pub seconds: f64,
}

/// The steps: the annealer's chains, each ordered breadth-first from what is placed before it,
/// cut into pieces of at most `piece` nodes, consecutive pieces packed while they fit. Every
/// node of a step is joined to the nodes placed before or to earlier nodes of its step. The
/// chain of fixed nodes, if any, is one step, uncut.
pub fn steps(level: &Level, piece: usize) -> Vec<Vec<NodeId>> {
    let adj = level.adjacency(&level.all_edges());
    let mut placed = vec![false; level.nodes.len()];
    let mut pieces: Vec<Vec<NodeId>> = Vec::new();
    for chain in anneal::chains(level) {
        let fixed = chain.iter().all(|n| level.nodes[n.0 as usize].position.is_some());
        let order = if fixed { chain.clone() } else { bfs_order(&adj, &chain, &placed) };
        for n in &order {
            placed[n.0 as usize] = true;
        }
        if fixed {
            pieces.push(order);
        } else {
            pieces.extend(order.chunks(piece.max(1)).map(<[NodeId]>::to_vec));
        }
    }
    let mut out: Vec<Vec<NodeId>> = Vec::new();
    for p in pieces {
        match out.last_mut() {
            Some(last) if last.len() + p.len() <= piece && !is_fixed_step(level, last) => last.extend(p),
            _ => out.push(p),
        }
    }
    out
}

fn is_fixed_step(level: &Level, step: &[NodeId]) -> bool {
    step.iter().all(|n| level.nodes[n.0 as usize].position.is_some())
}

/// `chain` breadth-first from its nodes next to a placed node (from its first node when none
/// is), through edges among the chain's nodes.
fn bfs_order(adj: &[Vec<NodeId>], chain: &[NodeId], placed: &[bool]) -> Vec<NodeId> {
    let inside: BTreeSet<NodeId> = chain.iter().copied().collect();
    let mut seen = BTreeSet::new();
    let mut q: VecDeque<NodeId> =
        chain.iter().copied().filter(|n| adj[n.0 as usize].iter().any(|m| placed[m.0 as usize])).collect();
    if q.is_empty() {
        q.push_back(chain[0]);
    }
    for n in &q {
        seen.insert(*n);
    }
    let mut out = Vec::new();
    while let Some(u) = q.pop_front() {
        out.push(u);
        for &v in &adj[u.0 as usize] {
            if inside.contains(&v) && seen.insert(v) {
                q.push_back(v);
            }
        }
    }
    // A chain is connected to what is placed; guard anyway.
    out.extend(chain.iter().copied().filter(|n| !seen.contains(n)));
    out
}

/// The x and y extent `[minx, maxx, miny, maxy]` of a block's polygon.
fn extent(level: &Level, b: BlockId) -> [f64; 4] {
    let p = &level.blocks[b.0 as usize].polygon;
    let f = |axis: usize, max: bool| {
        let it = p.iter().map(|q| q[axis]);
        if max {
            it.fold(f64::NEG_INFINITY, f64::max)
        } else {
            it.fold(f64::INFINITY, f64::min)
        }
    };
    [f(0, false), f(0, true), f(1, false), f(1, true)]
}

/// The model part of one step: the step's nodes, the placed nodes joined to them by an edge,
/// and the placed nodes whose blocks the step's blocks could reach (by the position bounds).
pub fn step_part(level: &Level, cs: &CSpaces, free: &[NodeId], placed: &[Option<(BlockId, P)>]) -> Part {
    let in_free: BTreeSet<NodeId> = free.iter().copied().collect();
    let touches = |e: &(NodeId, NodeId)| in_free.contains(&e.0) || in_free.contains(&e.1);
    let mut nodes: BTreeSet<NodeId> = in_free.clone();
    for &(a, b) in level.edges.iter().filter(|e| touches(e)) {
        for n in [a, b] {
            if placed[n.0 as usize].is_some() {
                nodes.insert(n);
            }
        }
    }
    let part = |nodes: &BTreeSet<NodeId>| {
        let nodes: Vec<NodeId> = nodes.iter().copied().collect();
        let edges: Vec<EdgeId> = (0..level.edges.len() as u32)
            .map(EdgeId)
            .filter(|e| {
                let (a, b) = level.edges[e.0 as usize];
                touches(&(a, b)) && nodes.binary_search(&a).is_ok() && nodes.binary_search(&b).is_ok()
            })
            .collect();
        let held = nodes.iter().filter_map(|&n| placed[n.0 as usize].map(|(b, p)| (n, b, p))).collect();
        Part { nodes, edges, placed: held }
    };
    let first = part(&nodes);
    let bounds = milp::bounds(level, cs, &first);
    // Where the step's blocks can be: each node's box grown by its blocks' extents.
    let reach: Vec<[f64; 4]> = first
        .nodes
        .iter()
        .zip(&bounds)
        .filter(|(n, _)| in_free.contains(n))
        .map(|(n, b)| {
            let e = level.nodes[n.0 as usize]
                .blocks
                .iter()
                .map(|&k| extent(level, k))
                .fold([f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY], |a, x| {
                    [a[0].min(x[0]), a[1].max(x[1]), a[2].min(x[2]), a[3].max(x[3])]
                });
            [b[0] + e[0], b[1] + e[1], b[2] + e[2], b[3] + e[3]]
        })
        .collect();
    let before = nodes.len();
    for (i, p) in placed.iter().enumerate() {
        let Some((b, at)) = p else { continue };
        let e = extent(level, *b);
        let f = [at[0] + e[0], at[0] + e[1], at[1] + e[2], at[1] + e[3]];
        let hit = reach.iter().any(|r| f[0] < r[1] && r[0] < f[1] && f[2] < r[3] && r[2] < f[3]);
        if hit {
            nodes.insert(NodeId(i as u32));
        }
    }
    if nodes.len() == before {
        first
    } else {
        part(&nodes)
    }
}

/// The direction a step grows in: from the centre of everything placed to the centre of the
/// placed nodes the step's nodes have doors to (none when nothing is placed or the two
/// coincide).
fn outward(level: &Level, part: &Part, step: &[NodeId], placed: &[Option<(BlockId, P)>]) -> Option<P> {
    let centre = |ps: &mut dyn Iterator<Item = P>| {
        let (mut sum, mut k) = ([0.0, 0.0], 0.0);
        for p in ps {
            sum = [sum[0] + p[0], sum[1] + p[1]];
            k += 1.0;
        }
        (k > 0.0).then(|| [sum[0] / k, sum[1] / k])
    };
    let all = centre(&mut placed.iter().flatten().map(|p| p.1))?;
    let joined =
        |n: NodeId| level.edges.iter().any(|&(a, b)| (a == n && step.contains(&b)) || (b == n && step.contains(&a)));
    let near = centre(&mut part.placed.iter().filter(|p| joined(p.0)).map(|p| p.2))?;
    let d = [near[0] - all[0], near[1] - all[1]];
    let len = (d[0] * d[0] + d[1] * d[1]).sqrt();
    (len > 1e-9).then(|| [d[0] / len, d[1] / len])
}

/// One step's model and its last point.
struct Solved {
    lm: LevelModel,
    x: Vec<f64>,
    cuts: usize,
}

/// Lays the level out step by step into `rep` (layouts, or a proof of infeasibility, or a
/// note), within the clock.
pub fn solve(
    level: &Level,
    cs: &CSpaces,
    o: &ExactOptions,
    clock: &Clock,
    rep: &mut ExactReport,
) -> Result<(), LevelError> {
    let t0 = clock.elapsed();
    let k = piece(level);
    let mut plan = steps(level, k);
    let mut st = Stats { steps: plan.len(), ..Stats::default() };
    let mut placed: Vec<Option<(BlockId, P)>> = vec![None; level.nodes.len()];
    let mut solved: Vec<Option<Solved>> = Vec::new();
    let mut retries = vec![0usize; plan.len()];
    let mut i = 0;
    while i < plan.len() {
        if clock.stopped() {
            rep.note = Some(format!("{} at step {} of {}", clock.why(), i + 1, plan.len()));
            break;
        }
        solved.truncate(i + 1);
        let answer = match solved.get_mut(i).and_then(Option::take) {
            Some(s) => solve_step(o, clock, s)?,
            None => {
                let part = step_part(level, cs, &plan[i], &placed);
                st.most_fixed = st.most_fixed.max(part.placed.len());
                let mut lm = milp::build(level, cs, &part);
                // A step merged after a failure closes cycles: no push, any layout will do.
                if plan[i].len() <= k {
                    if let Some(d) = outward(level, &part, &plan[i], &placed) {
                        lm.push_towards(d);
                    }
                }
                let a = solve_gap(&lm, o, clock.left().min(STEP_LIMIT), None, Some(PUSH_GAP))?;
                (a, lm)
            }
        };
        st.solves += 1;
        let (Answer { verdict, point, .. }, lm) = answer;
        rep.size = rep.size.max((lm.model.num_vars(), lm.model.num_rows()));
        if let (Verdict::Feasible, Some(x)) = (verdict, point) {
            st.largest_step = st.largest_step.max(plan[i].len());
            place(level, &lm, &x, &plan[i], &mut placed);
            let kept = Some(Solved { lm, x, cuts: 0 });
            if solved.len() > i {
                solved[i] = kept;
            } else {
                solved.push(kept);
            }
            i += 1;
            continue;
        }
        if clock.stopped() {
            continue; // the loop's head reports it
        }
        if i == 0 {
            if verdict == Verdict::Infeasible {
                // Nothing placed: the first step's nodes induce a subgraph without a layout.
                rep.time_to_proof = Some(clock.elapsed());
                if o.explain {
                    let nodes: Vec<NodeId> = plan[0].iter().copied().collect::<BTreeSet<_>>().into_iter().collect();
                    let part = Part::induced(level, nodes);
                    rep.conflict = Some(conflict(level, cs, o, &part.edges, clock)?);
                }
            } else {
                rep.note = Some("the first step went unanswered".into());
            }
            break;
        }
        // Back to the step before: merged with this one, or solved again differently.
        unplace(&plan[i - 1], &mut placed);
        if plan[i - 1].len() + plan[i].len() <= MERGE_FACTOR * k {
            let tail = plan.remove(i);
            plan[i - 1].extend(tail);
            retries.remove(i);
            solved.truncate(i - 1);
            st.merges += 1;
        } else if retries[i - 1] < RETRIES {
            retries[i - 1] += 1;
            st.retries += 1;
            if let Some(Some(s)) = solved.get_mut(i - 1) {
                s.cuts += 1;
                let c = s.cuts;
                let x = s.x.clone();
                s.lm.no_good(&x, c);
            }
            solved.truncate(i);
        } else {
            rep.note =
                Some(format!("step {} of {} failed after {RETRIES} retries of the step before", i + 1, plan.len()));
            break;
        }
        i -= 1;
    }
    st.seconds = clock.elapsed() - t0;
    if i == plan.len() {
        finish(level, o, clock, &plan, &mut placed, &mut solved, &mut st, rep)?;
    }
    rep.solves += st.solves;
    rep.incremental = Some(st);
    Ok(())
}

fn solve_step(o: &ExactOptions, clock: &Clock, s: Solved) -> Result<(Answer, LevelModel), LevelError> {
    let a = solve_once(&s.lm, o, clock.left().min(STEP_LIMIT), None)?;
    Ok((a, s.lm))
}

/// The step's nodes as the point places them.
fn place(level: &Level, lm: &LevelModel, x: &[f64], step: &[NodeId], placed: &mut [Option<(BlockId, P)>]) {
    let layout = lm.decode(level, x);
    let mine: BTreeSet<NodeId> = step.iter().copied().collect();
    for p in layout.nodes {
        let n = level.nodes.iter().position(|m| m.name == p.node).map(|k| NodeId(k as u32));
        if let Some(n) = n.filter(|n| mine.contains(n)) {
            placed[n.0 as usize] = Some((p.block, p.position));
        }
    }
}

fn unplace(step: &[NodeId], placed: &mut [Option<(BlockId, P)>]) {
    for n in step {
        placed[n.0 as usize] = None;
    }
}

/// The whole layout from the placements.
fn assemble(level: &Level, placed: &[Option<(BlockId, P)>]) -> Layout {
    let nodes = placed
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let (b, at) = p.unwrap_or((level.nodes[i].blocks[0], [0.0, 0.0]));
            Placement::new(level, NodeId(i as u32), b, at)
        })
        .collect();
    Layout { nodes }
}

/// Every node placed: the layout, and more by no-good cuts on the last step while the count
/// asks for them.
#[allow(clippy::too_many_arguments)]
fn finish(
    level: &Level,
    o: &ExactOptions,
    clock: &Clock,
    plan: &[Vec<NodeId>],
    placed: &mut [Option<(BlockId, P)>],
    solved: &mut [Option<Solved>],
    st: &mut Stats,
    rep: &mut ExactReport,
) -> Result<(), LevelError> {
    rep.layouts.push(checked(level, o, assemble(level, placed))?);
    let t = clock.elapsed();
    rep.time_to_first = Some(t);
    rep.time_to_last = Some(t);
    let (Some(last), Some(Some(s))) = (plan.last(), solved.last_mut()) else { return Ok(()) };
    while rep.layouts.len() < o.count {
        if clock.stopped() {
            rep.note = Some(format!(
                "{}: {} of {} layouts (variations of the last step)",
                clock.why(),
                rep.layouts.len(),
                o.count
            ));
            return Ok(());
        }
        if !s.lm.has_contacts() {
            break;
        }
        s.cuts += 1;
        let x = s.x.clone();
        s.lm.no_good(&x, s.cuts);
        let a = solve_once(&s.lm, o, clock.left().min(STEP_LIMIT), None)?;
        st.solves += 1;
        match (a.verdict, a.point) {
            (Verdict::Feasible, Some(x)) => {
                place(level, &s.lm, &x, last, placed);
                rep.layouts.push(checked(level, o, assemble(level, placed))?);
                rep.time_to_last = Some(clock.elapsed());
                s.x = x;
            }
            _ => break,
        }
    }
    if rep.layouts.len() < o.count {
        rep.note = Some(format!(
            "incremental: {} of {} layouts (distinct contacts of the last step only)",
            rep.layouts.len(),
            o.count
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::levels::generate::Generated;

    #[test]
    fn steps_cover_every_node_once_and_touch_what_is_before() {
        for family in ["grid:6x6", "ladder:20", "path:30", "tree:31", "caterpillar:5x2"] {
            let level = Generated::parse(family).unwrap().level(0.5).unwrap();
            let plan = steps(&level, 8);
            let mut seen = vec![false; level.nodes.len()];
            for (k, s) in plan.iter().enumerate() {
                assert!(!s.is_empty() && s.len() <= 8, "{family}: {s:?}");
                for (j, n) in s.iter().enumerate() {
                    let joined = k == 0 && j == 0
                        || level.edges.iter().any(|&(a, b)| {
                            let other = if a == *n {
                                b
                            } else if b == *n {
                                a
                            } else {
                                return false;
                            };
                            seen[other.0 as usize] || s[..j].contains(&other)
                        });
                    assert!(joined, "{family}: {n:?} of step {k}");
                }
                for n in s {
                    assert!(!seen[n.0 as usize]);
                    seen[n.0 as usize] = true;
                }
            }
            assert!(seen.iter().all(|&x| x), "{family}");
        }
    }
}
