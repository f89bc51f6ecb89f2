//! Exact tilings of a footprint by room templates: Knuth's Algorithm X with dancing links
//! (Knuth 2000, "Dancing Links"). Columns are the faces to cover, rows the placements. The
//! search branches on the column with the fewest rows left (random tie-break); rows are linked
//! large rooms first (fewer rooms, fewer walls), in a seeded random order among rooms of one size, so every seed
//! gives another tiling and a search that runs past its node limit is restarted with a new seed.
//! Room-type counts are honoured during the search: a template at its maximum is skipped, and
//! while a template is below its minimum the search first branches on where to put one more
//! (so an "exactly one boss room" is placed before the rest is tiled).

use super::budget;
use super::rng::Rng;
use crate::rules::placements::Placement;

/// The tiling problem: faces to cover, placements, counts.
pub(crate) struct TilingProblem<'a> {
    /// Placements (rows).
    pub placements: &'a [Placement],
    /// Placements the search may use.
    pub usable: Vec<bool>,
    /// Faces that must be covered exactly once (others must stay uncovered).
    pub cover: Vec<bool>,
    /// Per template: (min, max) count.
    pub counts: Vec<(Option<u32>, Option<u32>)>,
    /// Game levels: per placement, the vertices on its boundary where it has an inner edge (its
    /// possible portals). When given, a face's placements are tried in the order of how many
    /// portals they share with the rooms already placed (random tie-break), so neighbouring
    /// blocks line up and the block graph has the links a traversal needs.
    pub portals: Option<Vec<Vec<u32>>>,
}

const ROOT: usize = 0;

struct Dlx {
    l: Vec<usize>,
    r: Vec<usize>,
    u: Vec<usize>,
    d: Vec<usize>,
    col: Vec<usize>,
    row: Vec<usize>,
    size: Vec<usize>,
    /// First node of each row.
    row_head: Vec<usize>,
    covered: Vec<bool>,
    open: usize,
}

impl Dlx {
    fn cover(&mut self, c: usize) {
        self.covered[c] = true;
        self.open -= 1;
        let (l, r) = (self.l[c], self.r[c]);
        self.r[l] = r;
        self.l[r] = l;
        let mut i = self.d[c];
        let mut work = 1u64;
        while i != c {
            let mut j = self.r[i];
            while j != i {
                let (u, d) = (self.u[j], self.d[j]);
                self.d[u] = d;
                self.u[d] = u;
                self.size[self.col[j]] -= 1;
                j = self.r[j];
                work += 1;
            }
            i = self.d[i];
        }
        budget::charge_tight(work);
    }

    fn uncover(&mut self, c: usize) {
        let mut i = self.u[c];
        let mut work = 1u64;
        while i != c {
            let mut j = self.l[i];
            while j != i {
                self.size[self.col[j]] += 1;
                let (u, d) = (self.u[j], self.d[j]);
                self.d[u] = j;
                self.u[d] = j;
                j = self.l[j];
                work += 1;
            }
            i = self.u[i];
        }
        budget::charge_tight(work);
        let (l, r) = (self.l[c], self.r[c]);
        self.r[l] = c;
        self.l[r] = c;
        self.covered[c] = false;
        self.open += 1;
    }

    /// Covers every column of the row of node `i` other than `i`'s own (already covered).
    fn select_rest(&mut self, i: usize) {
        let mut j = self.r[i];
        while j != i {
            self.cover(self.col[j]);
            j = self.r[j];
        }
    }

    fn unselect_rest(&mut self, i: usize) {
        let mut j = self.l[i];
        while j != i {
            self.uncover(self.col[j]);
            j = self.l[j];
        }
    }
}

struct Search {
    dlx: Dlx,
    template: Vec<usize>,
    area: Vec<usize>,
    count: Vec<u32>,
    min: Vec<u32>,
    max: Vec<u32>,
    rows_of_template: Vec<Vec<usize>>,
    chosen: Vec<usize>,
    nodes: u64,
    node_limit: u64,
    rng: Rng,
    /// Per row: its portal vertices (empty without portal guidance).
    row_portals: Vec<Vec<u32>>,
    /// Per vertex: how many chosen rows have it as a portal.
    portal_count: Vec<u32>,
}

impl Search {
    fn row_alive(&self, row: usize) -> bool {
        let h = self.dlx.row_head[row];
        let mut j = h;
        loop {
            if self.dlx.covered[self.dlx.col[j]] {
                return false;
            }
            j = self.dlx.r[j];
            if j == h {
                return true;
            }
        }
    }

    /// Whether the templates below their minimum still fit in the faces left.
    fn mins_fit(&self) -> bool {
        let need: usize =
            (0..self.min.len()).map(|t| (self.min[t].saturating_sub(self.count[t])) as usize * self.area[t]).sum();
        need <= self.dlx.open
    }
}

/// Finds a tiling (placement indices, sorted), or `None` when the seeded search found none
/// within `node_limit` search nodes or there is none (call again with another seed).
pub(crate) fn tile(tp: &TilingProblem, seed: u64, node_limit: u64) -> Option<Vec<usize>> {
    let mut rng = Rng::new(seed);
    let nf = tp.cover.len();
    // Columns: one per face to cover.
    let mut col_of_face = vec![usize::MAX; nf];
    let mut ncols = 0;
    for (f, _) in tp.cover.iter().enumerate().filter(|(_, &c)| c) {
        ncols += 1;
        col_of_face[f] = ncols;
    }
    let ntemplates = tp.counts.len();
    let mut area = vec![0usize; ntemplates];
    let mut rows: Vec<usize> = Vec::new();
    for (k, pl) in tp.placements.iter().enumerate() {
        if pl.template < ntemplates {
            area[pl.template] = pl.faces.len();
        }
        if !tp.usable[k] || pl.faces.iter().any(|f| col_of_face[f.index()] == usize::MAX) {
            continue;
        }
        rows.push(k);
    }
    // Large rooms first, in random order among rooms of one size.
    let mut keyed: Vec<(f64, usize)> =
        rows.iter().map(|&k| (-(tp.placements[k].faces.len() as f64) - rng.unit(), k)).collect();
    keyed.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let rows: Vec<usize> = keyed.into_iter().map(|(_, k)| k).collect();

    let mut dlx = Dlx {
        l: (0..=ncols).map(|c| if c == 0 { ncols } else { c - 1 }).collect(),
        r: (0..=ncols).map(|c| if c == ncols { 0 } else { c + 1 }).collect(),
        u: (0..=ncols).collect(),
        d: (0..=ncols).collect(),
        col: (0..=ncols).collect(),
        row: vec![usize::MAX; ncols + 1],
        size: vec![0; ncols + 1],
        row_head: Vec::new(),
        covered: vec![false; ncols + 1],
        open: ncols,
    };
    let mut template = Vec::new();
    let mut rows_of_template = vec![Vec::new(); ntemplates];
    let mut row_placement = Vec::new();
    let mut row_portals = Vec::new();
    let mut nv = 0;
    for &k in &rows {
        let row = row_placement.len();
        row_placement.push(k);
        let ps = tp.portals.as_ref().map_or(Vec::new(), |p| p[k].clone());
        nv = nv.max(ps.iter().map(|&v| v as usize + 1).max().unwrap_or(0));
        row_portals.push(ps);
        template.push(tp.placements[k].template);
        rows_of_template[tp.placements[k].template].push(row);
        let first = dlx.l.len();
        let n = tp.placements[k].faces.len();
        for (j, f) in tp.placements[k].faces.iter().enumerate() {
            let c = col_of_face[f.index()];
            let node = first + j;
            dlx.l.push(if j == 0 { first + n - 1 } else { node - 1 });
            dlx.r.push(if j == n - 1 { first } else { node + 1 });
            let up = dlx.u[c];
            dlx.u.push(up);
            dlx.d.push(c);
            dlx.d[up] = node;
            dlx.u[c] = node;
            dlx.col.push(c);
            dlx.row.push(row);
            dlx.size[c] += 1;
        }
        dlx.row_head.push(first);
    }
    let min = tp.counts.iter().map(|c| c.0.unwrap_or(0)).collect();
    let max = tp.counts.iter().map(|c| c.1.unwrap_or(u32::MAX)).collect();
    let mut search = Search {
        dlx,
        template,
        area,
        count: vec![0; ntemplates],
        min,
        max,
        rows_of_template,
        chosen: Vec::new(),
        nodes: 0,
        node_limit,
        rng,
        row_portals,
        portal_count: vec![0; nv],
    };
    let found = search.solve_collect()?;
    let mut out: Vec<usize> = found.into_iter().map(|row| row_placement[row]).collect();
    out.sort_unstable();
    Some(out)
}

impl Search {
    fn mark(&mut self, row: usize, on: bool) {
        for &v in &self.row_portals[row] {
            if on {
                self.portal_count[v as usize] += 1;
            } else {
                self.portal_count[v as usize] -= 1;
            }
        }
    }

    /// Runs the search and returns the chosen rows of the first tiling found.
    fn solve_collect(&mut self) -> Option<Vec<usize>> {
        // `solve` unwinds `chosen` on its way back; record it at the moment of success.
        let mut found = None;
        self.solve_rec(&mut found);
        found
    }

    fn solve_rec(&mut self, found: &mut Option<Vec<usize>>) -> Option<bool> {
        self.nodes += 1;
        // Work (module `budget`): the node, and the scan of the open columns for the next one.
        budget::charge(1 + budget::tight(self.dlx.open as u64));
        if self.nodes > self.node_limit {
            return None;
        }
        if !self.mins_fit() {
            return Some(false);
        }
        if self.dlx.r[ROOT] == ROOT {
            let ok = (0..self.min.len()).all(|t| self.count[t] >= self.min[t]);
            if ok {
                *found = Some(self.chosen.clone());
            }
            return Some(ok);
        }
        if let Some(t) = (0..self.min.len()).find(|&t| self.count[t] < self.min[t]) {
            let mut rows: Vec<usize> =
                self.rows_of_template[t].iter().copied().filter(|&row| self.row_alive(row)).collect();
            self.rng.shuffle(&mut rows);
            for row in rows {
                let h = self.dlx.row_head[row];
                self.dlx.cover(self.dlx.col[h]);
                self.dlx.select_rest(h);
                self.count[t] += 1;
                self.chosen.push(row);
                self.mark(row, true);
                let res = self.solve_rec(found);
                self.mark(row, false);
                self.chosen.pop();
                self.count[t] -= 1;
                self.dlx.unselect_rest(h);
                self.dlx.uncover(self.dlx.col[h]);
                if res != Some(false) {
                    return res;
                }
            }
            return Some(false);
        }
        let mut best = usize::MAX;
        let mut ties = 0usize;
        let mut c = self.dlx.r[ROOT];
        let mut pick = c;
        while c != ROOT {
            let s = self.dlx.size[c];
            if s < best {
                best = s;
                pick = c;
                ties = 1;
            } else if s == best {
                ties += 1;
                if self.rng.below(ties) == 0 {
                    pick = c;
                }
            }
            c = self.dlx.r[c];
        }
        if best == 0 {
            return Some(false);
        }
        let c = pick;
        self.dlx.cover(c);
        let mut nodes = Vec::new();
        let mut i = self.dlx.d[c];
        while i != c {
            nodes.push(i);
            i = self.dlx.d[i];
        }
        if !self.portal_count.is_empty() {
            // Rows sharing more portals with the blocks placed first (a stable sort keeps the
            // seeded order among equals).
            let score =
                |row: usize| self.row_portals[row].iter().filter(|&&v| self.portal_count[v as usize] > 0).count();
            let mut keyed: Vec<(usize, usize)> =
                nodes.iter().map(|&i| (usize::MAX - score(self.dlx.row[i]), i)).collect();
            keyed.sort_by_key(|k| k.0);
            nodes = keyed.into_iter().map(|k| k.1).collect();
        }
        let mut result = Some(false);
        for i in nodes {
            let row = self.dlx.row[i];
            let t = self.template[row];
            if self.count[t] < self.max[t] {
                self.dlx.select_rest(i);
                self.count[t] += 1;
                self.chosen.push(row);
                self.mark(row, true);
                let res = self.solve_rec(found);
                self.mark(row, false);
                self.chosen.pop();
                self.count[t] -= 1;
                self.dlx.unselect_rest(i);
                if res != Some(false) {
                    result = res;
                    break;
                }
            }
        }
        self.dlx.uncover(c);
        result
    }
}
