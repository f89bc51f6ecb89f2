//! The bridge from a laid-out level to the network IP: a mesh over the placed blocks and a spec
//! (`netspec solve`'s input) whose network may pass from block to block only through doors.
//!
//! The mesh is one tensor grid over the whole layout: every x and y of a block corner and of a
//! door's midpoint is a grid line, and between them lines `spacing` apart (a lattice line closer
//! than a quarter spacing to one of those is left out). A cell belongs to the block that holds its
//! centre; cells outside every block are left out. Walls are therefore mesh edges, every door has
//! a grid vertex at its midpoint, and neighbouring blocks share their wall vertices. Where two
//! blocks meet only at a corner (a vertex whose two cells touch diagonally), one cell loses that
//! corner (it becomes a triangle), so the mesh stays manifold; a cell keeps at most one such cut.
//!
//! The spec keeps the network inside the blocks and makes it pass between them only through
//! doors: the mesh boundary is `wall`; every grid edge between two different blocks is an
//! obstacle edge; every vertex on such a wall is an obstacle vertex unless it lies on the door of
//! a graph edge between exactly those two blocks (the door-wide piece centred on their shared
//! wall, as `netspec level` draws it). Every room is visited: the interior vertex nearest its
//! block's centroid is forced active, and the entrance's is the one sink. Dead-ends are allowed
//! (a room can be the end of a path). Coverage (Euclidean) defaults to the smallest range of at
//! least 1 that the forced room vertices already satisfy, so the IP finds the shortest network
//! through all rooms; a smaller range makes the network sweep the rooms.

use super::spec::{Level, NodeId};
use super::validate::{door, validate};
use super::{Layout, LevelError};
use crate::geometry::convex::{self, LEN_TOL};
use crate::geometry::{self, P};
use crate::mesh::{Mesh, VertexId};
use crate::spec::{
    Allow, BoundaryRole, CoverageModel, CoverageSpec, FeatureSpec, MeshSpec, Place, SinkSpec, Spec, UserSpec,
};
use serde::Serialize;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// The mesh file the spec names (beside it).
pub const MESH_FILE: &str = "mesh.json";
/// The spec file.
pub const SPEC_FILE: &str = "network.toml";
/// Most grid cells the export scans.
const MAX_CELLS: usize = 1 << 22;
/// Coordinates of corners and doors closer than this are one grid line.
const MERGE_TOL: f64 = 1e-6;

/// How to export a layout.
#[derive(Clone, Debug, PartialEq)]
pub struct BridgeOptions {
    /// Grid spacing inside the blocks (level units; the door width when `None`).
    pub spacing: Option<f64>,
    /// The node whose room holds the sink (the first node when `None`).
    pub entrance: Option<String>,
    /// Coverage range (Euclidean, level units, at least 1; when `None` the smallest such range
    /// that the forced room vertices satisfy).
    pub coverage: Option<f64>,
}

/// A door: the door-wide piece of the wall two graph neighbours share.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Door {
    /// The two nodes.
    pub nodes: [String; 2],
    /// The door's two ends.
    pub span: [P; 2],
}

/// A layout exported for the network IP.
#[derive(Clone, Debug)]
pub struct Bridge {
    /// The mesh over the placed blocks.
    pub mesh: Mesh,
    /// The spec; its mesh is [`MESH_FILE`], beside it.
    pub spec: Spec,
    /// The placed polygon of every node, in node order.
    pub blocks: Vec<Vec<P>>,
    /// Every graph edge's door, in edge order.
    pub doors: Vec<Door>,
    /// The forced vertex of every node's room, in node order (the entrance's is the sink).
    pub rooms: Vec<VertexId>,
    /// The node with the sink.
    pub entrance: String,
}

fn field(name: &str, reason: String) -> LevelError {
    LevelError::Field { field: name.into(), reason }
}

impl BridgeOptions {
    /// The options checked against `level` (before anything is laid out): the grid spacing and
    /// the entrance node.
    pub fn check(&self, level: &Level) -> Result<(f64, NodeId), LevelError> {
        let spacing = self.spacing.unwrap_or(level.door_width);
        if !(spacing.is_finite() && spacing > 0.0) {
            return Err(field("spacing", format!("must be a positive number, got {spacing}")));
        }
        if let Some(r) = self.coverage.filter(|r| !(r.is_finite() && *r >= 1.0)) {
            return Err(field("coverage", format!("must be a finite number of at least 1, got {r}")));
        }
        let entrance = match &self.entrance {
            None => NodeId(0),
            Some(e) => (0..level.nodes.len() as u32)
                .map(NodeId)
                .find(|&n| level.node_name(n) == e)
                .ok_or_else(|| field("entrance", format!("no node is named {e:?}")))?,
        };
        Ok((spacing, entrance))
    }
}

/// Exports `layout` of `level` as a mesh and a spec named `name`.
pub fn bridge(level: &Level, layout: &Layout, name: &str, o: &BridgeOptions) -> Result<Bridge, LevelError> {
    let (spacing, entrance) = o.check(level)?;
    let blocks = placed(level, layout)?;
    let doors = doors(level, layout)?;
    let grid = Grid::new(&blocks, &doors, spacing)?;
    let (mesh, owners) = grid.mesh()?;
    let walls = Walls::new(&mesh, &owners, level, &doors);
    let rooms = rooms(level, &blocks, &mesh, &owners, spacing)?;
    let coverage = match o.coverage {
        Some(r) => r,
        None => implied_coverage(&mesh, &rooms, &walls.vertices),
    };
    let forced = (0..rooms.len()).filter(|&i| i != entrance.0 as usize).map(|i| Place::Vertex(rooms[i].0)).collect();
    let spec = Spec {
        name: name.to_string(),
        description: format!(
            "Paths through a laid-out level: {} rooms, doors {} wide, grid spacing {}, entrance {}",
            level.nodes.len(),
            level.door_width,
            spacing,
            level.node_name(entrance)
        ),
        mesh: MeshSpec { grid: None, clipped: None, file: Some(MESH_FILE.into()), jitter: None },
        boundary: BoundaryRole::Wall,
        sinks: SinkSpec { vertices: vec![rooms[entrance.0 as usize].0], ..SinkSpec::default() },
        coverage: CoverageSpec { range: coverage, model: CoverageModel::Euclidean },
        weights: Default::default(),
        features: FeatureSpec { dead_ends: Allow::Allow, branches: Allow::Allow },
        point_to_point: None,
        user: UserSpec {
            obstacle_vertices: walls.vertices.iter().map(|v| v.0).collect(),
            obstacle_edges: walls.edges,
            forced_vertices: forced,
            ..UserSpec::default()
        },
        rooms: None,
        formulation: Default::default(),
        solver: Default::default(),
    };
    let doors = level
        .edges
        .iter()
        .zip(doors)
        .map(|(&(a, b), span)| Door { nodes: [level.node_name(a).into(), level.node_name(b).into()], span })
        .collect();
    Ok(Bridge { mesh, spec, blocks, doors, rooms, entrance: level.node_name(entrance).into() })
}

/// Writes [`MESH_FILE`] and [`SPEC_FILE`] into `dir` (created if missing).
pub fn write(dir: &Path, b: &Bridge) -> Result<Vec<PathBuf>, LevelError> {
    let err = |p: &Path, e: String| LevelError::Write { path: p.display().to_string(), reason: e };
    std::fs::create_dir_all(dir).map_err(|e| err(dir, e.to_string()))?;
    let mesh_path = dir.join(MESH_FILE);
    let json = serde_json::to_string(&b.mesh).map_err(|e| err(&mesh_path, e.to_string()))?;
    std::fs::write(&mesh_path, json).map_err(|e| err(&mesh_path, e.to_string()))?;
    let spec_path = dir.join(SPEC_FILE);
    let text = toml::to_string(&b.spec).map_err(|e| err(&spec_path, e.to_string()))?;
    let header = "# Exported by `netspec level --export-spec`: solve with `netspec solve` (docs/levels.md).\n";
    std::fs::write(&spec_path, format!("{header}{text}")).map_err(|e| err(&spec_path, e.to_string()))?;
    Ok(vec![mesh_path, spec_path])
}

/// The placed polygons, each with axis-parallel walls only.
fn placed(level: &Level, layout: &Layout) -> Result<Vec<Vec<P>>, LevelError> {
    let mut out = Vec::new();
    for p in &layout.nodes {
        let poly = convex::translate(&level.blocks[p.block.0 as usize].polygon, p.position);
        let slanted = (0..poly.len()).any(|i| {
            let d = geometry::sub(poly[(i + 1) % poly.len()], poly[i]);
            d[0].abs() > LEN_TOL && d[1].abs() > LEN_TOL
        });
        if slanted {
            let k = p.block.0 as usize;
            return Err(field(
                &format!("block[{k}] ({:?}).polygon", level.blocks[k].name),
                "the export to a network spec needs axis-parallel walls (this block has a slanted one)".into(),
            ));
        }
        out.push(poly);
    }
    Ok(out)
}

/// Every graph edge's door (the layout must pass the validator).
fn doors(level: &Level, layout: &Layout) -> Result<Vec<[P; 2]>, LevelError> {
    let v = validate(level, layout);
    if !v.is_valid() {
        return Err(LevelError::Rejected(format!("the layout to export is invalid: {}", v.problems().join("; "))));
    }
    level
        .all_edges()
        .into_iter()
        .map(|e| door(level, &v, e).ok_or_else(|| LevelError::Rejected(format!("edge {} has no door", e.0))))
        .collect()
}

/// Sorted distinct values, those closer than `tol` to the previous kept one merged into it.
fn merged(mut v: Vec<f64>, tol: f64) -> Vec<f64> {
    v.sort_by(f64::total_cmp);
    let mut out: Vec<f64> = Vec::new();
    for x in v {
        if out.last().is_none_or(|&l| x - l > tol) {
            out.push(x);
        }
    }
    out
}

/// The grid lines along one axis: the essential coordinates and the lattice between them.
fn lines(essential: Vec<f64>, spacing: f64) -> Vec<f64> {
    let ess = merged(essential, MERGE_TOL);
    let (lo, hi) = (ess[0], ess[ess.len() - 1]);
    let mut all = ess.clone();
    let steps = ((hi - lo) / spacing).floor() as usize;
    for k in 1..=steps {
        let x = lo + k as f64 * spacing;
        let i = ess.partition_point(|&e| e < x);
        let near = [i.checked_sub(1), Some(i)].into_iter().flatten().filter_map(|j| ess.get(j));
        if near.clone().all(|&e| (e - x).abs() > spacing / 4.0) {
            all.push(x);
        }
    }
    merged(all, 0.0)
}

/// The tensor grid and which block owns each cell.
struct Grid {
    xs: Vec<f64>,
    ys: Vec<f64>,
    /// Per cell (row-major, bottom row first): the owning node.
    owner: Vec<Option<usize>>,
}

impl Grid {
    fn new(blocks: &[Vec<P>], doors: &[[P; 2]], spacing: f64) -> Result<Grid, LevelError> {
        let mids = doors.iter().map(|d| geometry::scale(geometry::add(d[0], d[1]), 0.5));
        let pts: Vec<P> = blocks.iter().flatten().copied().chain(mids).collect();
        let xs = lines(pts.iter().map(|p| p[0]).collect(), spacing);
        let ys = lines(pts.iter().map(|p| p[1]).collect(), spacing);
        let (nx, ny) = (xs.len() - 1, ys.len() - 1);
        if nx.saturating_mul(ny) > MAX_CELLS {
            return Err(field(
                "spacing",
                format!("{spacing} gives a grid of {nx} × {ny} cells (at most {MAX_CELLS}); choose a larger one"),
            ));
        }
        let boxes: Vec<[f64; 4]> = blocks.iter().map(|b| convex::bounding_box(b)).collect();
        let mut owner = vec![None; nx * ny];
        for j in 0..ny {
            for i in 0..nx {
                let c = [(xs[i] + xs[i + 1]) / 2.0, (ys[j] + ys[j + 1]) / 2.0];
                owner[j * nx + i] = (0..blocks.len()).find(|&k| {
                    let b = boxes[k];
                    c[0] > b[0]
                        && c[0] < b[1]
                        && c[1] > b[2]
                        && c[1] < b[3]
                        && crate::geometry::ring_contains(&blocks[k], c)
                });
            }
        }
        Ok(Grid { xs, ys, owner })
    }

    fn nx(&self) -> usize {
        self.xs.len() - 1
    }

    fn ny(&self) -> usize {
        self.ys.len() - 1
    }

    /// The owner of cell `(i, j)`, `None` outside the grid or every block.
    fn cell(&self, i: isize, j: isize) -> Option<usize> {
        if i < 0 || j < 0 || i as usize >= self.nx() || j as usize >= self.ny() {
            return None;
        }
        self.owner[j as usize * self.nx() + i as usize]
    }

    /// The mesh of the owned cells (corner cuts where blocks touch diagonally), and the owner
    /// of every face.
    fn mesh(&self) -> Result<(Mesh, Vec<usize>), LevelError> {
        let (nx, ny) = (self.nx(), self.ny());
        // Corners cut from cells: (cell, corner index in [bl, br, tr, tl]).
        let mut cut: Vec<Option<usize>> = vec![None; nx * ny];
        for j in 0..=ny as isize {
            for i in 0..=nx as isize {
                let around = [(i - 1, j - 1), (i, j - 1), (i, j), (i - 1, j)];
                let kept = around.map(|(a, b)| self.cell(a, b).is_some());
                // Cells 0 and 2, or 1 and 3, alone at this grid point.
                let pair = match kept {
                    [true, false, true, false] => [0, 2],
                    [false, true, false, true] => [1, 3],
                    _ => continue,
                };
                // The corner of cell k at this point: cell 0 has it top-right (2), 1 top-left (3),
                // 2 bottom-left (0), 3 bottom-right (1).
                let corner = [2, 3, 0, 1];
                let free = pair.iter().copied().find(|&k| {
                    let (a, b) = around[k];
                    cut[b as usize * nx + a as usize].is_none()
                });
                let Some(k) = free else {
                    return Err(field(
                        "spacing",
                        format!(
                            "blocks touch at corners too close together near ({}, {})",
                            self.xs[i as usize], self.ys[j as usize]
                        ),
                    ));
                };
                let (a, b) = around[k];
                cut[b as usize * nx + a as usize] = Some(corner[k]);
            }
        }
        let nvx = nx + 1;
        let mut vid = vec![u32::MAX; nvx * (ny + 1)];
        let mut positions = Vec::new();
        let mut faces = Vec::new();
        let mut owners = Vec::new();
        for j in 0..ny {
            for i in 0..nx {
                let Some(o) = self.owner[j * nx + i] else { continue };
                let mut face = Vec::with_capacity(4);
                for (k, (di, dj)) in [(0, 0), (1, 0), (1, 1), (0, 1)].into_iter().enumerate() {
                    if cut[j * nx + i] == Some(k) {
                        continue;
                    }
                    let g = (j + dj) * nvx + i + di;
                    if vid[g] == u32::MAX {
                        vid[g] = positions.len() as u32;
                        positions.push([self.xs[i + di], self.ys[j + dj]]);
                    }
                    face.push(vid[g]);
                }
                faces.push(face);
                owners.push(o);
            }
        }
        if faces.is_empty() {
            return Err(LevelError::Rejected("the layout's blocks cover no grid cell".into()));
        }
        let mesh = Mesh::from_polygons(positions, faces)
            .map_err(|e| LevelError::Rejected(format!("the exported mesh is invalid: {e}")))?;
        Ok((mesh, owners))
    }
}

/// The nodes whose blocks hold each vertex (the owners of its faces), sorted.
fn vertex_owners(mesh: &Mesh, face_owner: &[usize]) -> Vec<BTreeSet<usize>> {
    let mut out = vec![BTreeSet::new(); mesh.num_vertices()];
    for f in mesh.faces() {
        for v in mesh.face_vertices(f) {
            out[v.index()].insert(face_owner[f.index()]);
        }
    }
    out
}

/// What the network may not cross: wall edges between blocks and wall vertices off the doors.
struct Walls {
    vertices: Vec<VertexId>,
    edges: Vec<[u32; 2]>,
}

impl Walls {
    fn new(mesh: &Mesh, face_owner: &[usize], level: &Level, doors: &[[P; 2]]) -> Walls {
        let owners = vertex_owners(mesh, face_owner);
        let mut vertices = Vec::new();
        for v in mesh.vertices() {
            let o = &owners[v.index()];
            if o.len() < 2 {
                continue;
            }
            let p = mesh.position(v);
            let on_door = level.edges.iter().zip(doors).any(|(&(a, b), d)| {
                o.len() == 2 && o.contains(&(a.0 as usize)) && o.contains(&(b.0 as usize)) && on_segment(p, d)
            });
            if !on_door {
                vertices.push(v);
            }
        }
        let mut edges = Vec::new();
        for e in mesh.edges() {
            let [l, r] = mesh.edge_faces(e);
            if let (Some(l), Some(r)) = (l, r) {
                if face_owner[l.index()] != face_owner[r.index()] {
                    let (a, b) = mesh.edge_vertices(e);
                    edges.push([a.0, b.0]);
                }
            }
        }
        Walls { vertices, edges }
    }
}

/// Whether `p` lies on segment `s` (within [`MERGE_TOL`]).
pub fn on_segment(p: P, s: &[P; 2]) -> bool {
    let d = geometry::sub(s[1], s[0]);
    let len = convex::length(d);
    if len < LEN_TOL {
        return convex::length(geometry::sub(p, s[0])) <= MERGE_TOL;
    }
    let t = geometry::dot(geometry::sub(p, s[0]), d) / len;
    let off = geometry::cross(d, geometry::sub(p, s[0])).abs() / len;
    off <= MERGE_TOL && t >= -MERGE_TOL && t <= len + MERGE_TOL
}

/// Each node's room vertex: the vertex off the mesh boundary and inside its block alone that is
/// nearest the block's centroid (the smallest id on a tie).
fn rooms(
    level: &Level,
    blocks: &[Vec<P>],
    mesh: &Mesh,
    face_owner: &[usize],
    spacing: f64,
) -> Result<Vec<VertexId>, LevelError> {
    let owners = vertex_owners(mesh, face_owner);
    let mut out = Vec::new();
    for (k, poly) in blocks.iter().enumerate() {
        let c = crate::geometry::centroid(poly);
        let best = mesh
            .vertices()
            .filter(|&v| !mesh.is_boundary_vertex(v) && owners[v.index()].len() == 1 && owners[v.index()].contains(&k))
            .map(|v| (convex::length(geometry::sub(mesh.position(v), c)), v))
            .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        match best {
            Some((_, v)) => out.push(v),
            None => {
                return Err(field(
                    "spacing",
                    format!(
                        "{spacing} leaves no grid vertex inside the room of {:?}; choose a smaller one",
                        level.node_name(NodeId(k as u32))
                    ),
                ))
            }
        }
    }
    Ok(out)
}

/// The smallest Euclidean coverage range of at least 1 (the spec's minimum) that the room
/// vertices alone satisfy: the largest distance from a vertex that is not an obstacle to the
/// nearest room vertex.
fn implied_coverage(mesh: &Mesh, rooms: &[VertexId], obstacles: &[VertexId]) -> f64 {
    let blocked: BTreeSet<VertexId> = obstacles.iter().copied().collect();
    let nearest = |v: VertexId| {
        let p = mesh.position(v);
        rooms.iter().map(|&r| convex::length(geometry::sub(mesh.position(r), p))).fold(f64::INFINITY, f64::min)
    };
    mesh.vertices().filter(|v| !blocked.contains(v)).map(nearest).fold(1.0, f64::max)
}
