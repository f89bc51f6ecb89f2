//! The picture of a design: its mesh, rooms, network and points as a plain
//! [`NetworkScene`], drawn by [`crate::render::network`].

use super::{travel_distances, Network};
use crate::geometry as geom;
use crate::mesh::{EdgeId, FaceId, Mesh};
use crate::render::network::{self, ActiveEdge, NetworkScene, Room, RoomType};
use crate::render::Caption;
use crate::rules::paths::PathSets;
use crate::rules::placements::Placement;
use crate::spec::Problem;

fn edge(mesh: &Mesh, e: EdgeId) -> [u32; 2] {
    let (a, b) = mesh.edge_vertices(e);
    [a.0, b.0]
}

/// A spec's mesh and what it places on it, without a design: the mesh, obstacle faces and
/// vertices, sinks, forced edges and vertices, and the edges of the through routes. The base of
/// [`network_scene`] and of the conflict picture (`explain::conflict_svg`).
pub fn mesh_scene(p: &Problem) -> NetworkScene {
    let mesh = &p.mesh;
    let mut forced_edges: Vec<[u32; 2]> = p.forced_edges.iter().map(|&e| edge(mesh, e)).collect();
    for r in &p.through_routes {
        for w2 in r.windows(2) {
            if let Some(h) = mesh.half_edge_between(w2[0], w2[1]) {
                forced_edges.push(edge(mesh, mesh.he_edge(h)));
            }
        }
    }
    NetworkScene {
        positions: mesh.positions().to_vec(),
        edges: mesh.edges().map(|e| edge(mesh, e)).collect(),
        faces: mesh.faces().map(|f| mesh.face_vertices(f).iter().map(|v| v.0).collect()).collect(),
        obstacle_faces: mesh.faces().filter(|f| p.is_obstacle_face[f.index()]).map(|f| f.0).collect(),
        obstacle_vertices: mesh.vertices().filter(|v| p.is_obstacle_vertex[v.index()]).map(|v| v.0).collect(),
        sinks: mesh.vertices().filter(|v| p.is_sink[v.index()]).map(|v| v.0).collect(),
        samples: None,
        forced_edges,
        forced_vertices: p.forced_vertices.iter().map(|v| v.0).collect(),
        through_routes: !p.through_routes.is_empty(),
        ..NetworkScene::default()
    }
}

/// Where a room's letter goes: its bounding-box centre, or the centroid of its face nearest to
/// it when the centre is outside the room (L and T shapes).
fn label_point(mesh: &Mesh, pl: &Placement) -> [f64; 2] {
    let pts: Vec<[f64; 2]> =
        pl.faces.iter().flat_map(|&f| mesh.face_vertices(f).iter().map(|&v| mesh.position(v))).collect();
    let (lo, hi) = pts.iter().fold(([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]), |(lo, hi), q| {
        ([lo[0].min(q[0]), lo[1].min(q[1])], [hi[0].max(q[0]), hi[1].max(q[1])])
    });
    let centre = [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0];
    let polygon = |f: FaceId| -> Vec<[f64; 2]> { mesh.face_vertices(f).iter().map(|&v| mesh.position(v)).collect() };
    if pl.faces.iter().any(|&f| geom::ring_contains(&polygon(f), centre)) {
        centre
    } else {
        pl.faces
            .iter()
            .map(|&f| mesh.face_centroid(f))
            .min_by(|a, b| geom::dist(*a, centre).total_cmp(&geom::dist(*b, centre)))
            .unwrap_or(centre)
    }
}

/// The scene of a design: [`mesh_scene`] with the active edges coloured by the true network
/// distance to the nearest sink (computed from the design, never the solver's labels, which only
/// (2) defines and which are not distances off the optimum), the point-to-point samples of
/// `paths`, and the chosen rooms (`net.rooms`, indices into `placements`) with their types.
pub fn network_scene(
    p: &Problem,
    net: &Network,
    paths: Option<&PathSets>,
    placements: Option<&[Placement]>,
) -> NetworkScene {
    let mesh = &p.mesh;
    let mut scene = mesh_scene(p);
    scene.samples = paths.map(|ps| ps.samples.iter().map(|&(_, v)| v.0).collect());
    let travel = travel_distances(mesh, net, &p.is_sink);
    scene.active = net
        .active_edges()
        .into_iter()
        .map(|e| {
            let (a, b) = mesh.edge_vertices(e);
            ActiveEdge { edge: [a.0, b.0], distance: travel[a.index()].max(travel[b.index()]) }
        })
        .collect();
    scene.distance_max = scene.active.iter().map(|a| a.distance).filter(|d| d.is_finite()).fold(0.0, f64::max);
    if let Some(rooms) = &p.rooms {
        scene.room_types = rooms
            .templates
            .iter()
            .zip(&rooms.colors)
            .map(|(t, colour)| RoomType { name: t.name.clone(), colour: colour.clone() })
            .collect();
        if let Some(pls) = placements {
            scene.rooms = net
                .rooms
                .iter()
                .map(|&k| {
                    let pl = &pls[k];
                    Room {
                        faces: pl.faces.iter().map(|f| f.0).collect(),
                        boundary_edges: pl.boundary_edges.iter().map(|&e| edge(mesh, e)).collect(),
                        template: pl.template,
                        label_at: label_point(mesh, pl),
                    }
                })
                .collect();
        }
    }
    scene
}

/// Draws the design as SVG text ([`network_scene`] drawn by [`crate::render::network::svg`]).
/// `placements` are the model's room placements (when tiling rooms); the chosen ones
/// (`net.rooms`) are filled with their template's colour and marked with its letter. The legend
/// lists only what is drawn.
pub fn network_svg(
    p: &Problem,
    net: &Network,
    paths: Option<&PathSets>,
    placements: Option<&[Placement]>,
    caption: &Caption,
) -> String {
    network::svg(&network_scene(p, net, paths, placements), caption)
}
