use super::*;
use crate::geometry::{self, cdt};
use std::f64::consts::PI;

fn square() -> Polygon {
    Polygon::new(vec![[0.0, 0.0], [100.0, 0.0], [100.0, 100.0], [0.0, 100.0]], vec![]).unwrap()
}

fn l_shape() -> Polygon {
    let outer = vec![[0.0, 0.0], [100.0, 0.0], [100.0, 50.0], [50.0, 50.0], [50.0, 100.0], [0.0, 100.0]];
    Polygon::new(outer, vec![]).unwrap()
}

fn regular(n: usize, r: f64) -> Polygon {
    // A quarter-step rotation keeps the pentagon's edges off the axes (nothing special about 0°).
    let ring =
        (0..n).map(|k| (2.0 * PI * (k as f64 + 0.25) / n as f64).sin_cos()).map(|(s, c)| [r * c, r * s]).collect();
    Polygon::new(ring, vec![]).unwrap()
}

fn annulus() -> Polygon {
    let hole = vec![[30.0, 30.0], [70.0, 30.0], [70.0, 70.0], [30.0, 70.0]];
    Polygon::new(vec![[0.0, 0.0], [100.0, 0.0], [100.0, 100.0], [0.0, 100.0]], vec![hole]).unwrap()
}

fn field(region: &Polygon, method: FieldMethod, h: f64) -> CrossField {
    CrossField::new(region, &FieldOptions { method, h }).unwrap()
}

/// `χ − Σ_c (2 − k_c)/4`, `k_c = round(θ_c / 90°)` over the corners of every ring.
fn poincare_hopf(region: &Polygon) -> f64 {
    let chi = 1.0 - region.holes().len() as f64;
    let mut corners = 0.0;
    for ring in region.rings() {
        let n = ring.len();
        for i in 0..n {
            let (a, b, c) = (ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]);
            let (u, v) = (geometry::sub(b, a), geometry::sub(c, b));
            let turn = geometry::cross(u, v).atan2(geometry::dot(u, v));
            let interior = PI - turn;
            corners += (2.0 - (interior / (PI / 2.0)).round()) / 4.0;
        }
    }
    chi - corners
}

/// (positive, negative) singularity counts, each singularity ±1/4.
fn counts(f: &CrossField) -> (usize, usize) {
    assert!(f.singularities().iter().all(|s| s.index.abs() == 0.25), "{:?}", f.singularities());
    let pos = f.singularities().iter().filter(|s| s.index > 0.0).count();
    (pos, f.singularities().len() - pos)
}

fn check_shapes(method: FieldMethod) {
    let cases: [(&str, Polygon, f64, (usize, usize)); 6] = [
        ("square", square(), 5.0, (0, 0)),
        ("L-shape", l_shape(), 5.0, (0, 0)),
        ("triangle", regular(3, 60.0), 4.0, (1, 0)),
        ("pentagon", regular(5, 60.0), 4.0, (0, 1)),
        ("disc", regular(64, 60.0), 4.0, (4, 0)),
        ("annulus", annulus(), 5.0, (0, 0)),
    ];
    for (name, region, h, expected) in cases {
        let f = field(&region, method, h);
        let total: f64 = f.singularities().iter().map(|s| s.index).sum();
        assert_eq!(total, poincare_hopf(&region), "{name} ({method:?}): {:?}", f.singularities());
        assert_eq!(counts(&f), expected, "{name} ({method:?}): {:?}", f.singularities());
        for s in f.singularities() {
            assert!(region.contains(s.at), "{name}: {s:?}");
        }
    }
}

#[test]
fn poincare_hopf_with_corners_smooth() {
    check_shapes(FieldMethod::Smooth);
}

#[test]
fn poincare_hopf_with_corners_distance() {
    check_shapes(FieldMethod::Distance);
}

#[test]
fn corner_formula_matches_the_expected_totals() {
    assert_eq!(poincare_hopf(&square()), 0.0);
    assert_eq!(poincare_hopf(&l_shape()), 0.0);
    assert_eq!(poincare_hopf(&regular(3, 1.0)), 0.25);
    assert_eq!(poincare_hopf(&regular(5, 1.0)), -0.25);
    assert_eq!(poincare_hopf(&regular(64, 1.0)), 1.0);
    assert_eq!(poincare_hopf(&annulus()), 0.0);
}

/// `u = z − z₀` has one `+1/4` at `z₀`, `u = conj(z − z₀)` one `−1/4`, on counter-clockwise
/// triangles.
#[test]
fn singularity_signs_follow_orientation() {
    let mesh = cdt::triangulate(&square(), 10.0).unwrap();
    let z0 = [43.3, 51.7];
    for (sign, expected) in [(1.0, 0.25), (-1.0, -0.25)] {
        let power: Vec<C> = mesh.vertices.iter().map(|p| [p[0] - z0[0], sign * (p[1] - z0[1])]).collect();
        let f = CrossField::from_power(FieldMethod::Smooth, 10.0, vec![], mesh.clone(), power);
        assert_eq!(f.singularities().len(), 1, "{:?}", f.singularities());
        let s = f.singularities()[0];
        assert_eq!(s.index, expected);
        assert_eq!(f.locate(z0), Some(s.triangle));
        assert!(geometry::dist(s.at, z0) < 10.0);
    }
}

#[test]
fn direction_is_a_unit_arm_within_45_degrees() {
    let f = field(&regular(5, 60.0), FieldMethod::Smooth, 4.0);
    for k in 0..50 {
        let a = k as f64 * 0.37;
        let p = [20.0 * (0.7 * a).cos(), 20.0 * (1.3 * a).sin()];
        let along = [a.cos() * 3.0, a.sin() * 3.0];
        let d = f.direction(p, along).unwrap();
        assert!((geometry::norm(d) - 1.0).abs() < 1e-12);
        let cos = geometry::dot(d, along) / 3.0;
        assert!(cos >= (PI / 4.0).cos() - 1e-12, "{p:?} {along:?} {d:?}");
        let s = f.sample(p).unwrap();
        let off = (d[1].atan2(d[0]) - s.theta).rem_euclid(PI / 2.0);
        assert!(off.min(PI / 2.0 - off) < 1e-9);
    }
}

#[test]
fn locate_and_sample_stay_in_the_region() {
    let f = field(&annulus(), FieldMethod::Distance, 5.0);
    assert_eq!(f.locate([50.0, 50.0]), None, "in the hole");
    assert_eq!(f.locate([-1.0, 50.0]), None);
    assert_eq!(f.locate([f64::NAN, 50.0]), None);
    assert_eq!(f.sample([150.0, 50.0]), None);
    for p in [[10.0, 10.0], [0.0, 0.0], [99.9, 50.0], [30.0, 30.0], [15.0, 85.0]] {
        let t = f.locate(p).unwrap();
        let l = grid::barycentric(f.vertices(), f.triangles()[t], p);
        assert!(l.iter().all(|&x| x >= -1e-9), "{p:?} {l:?}");
        assert_eq!(f.sample(p).unwrap().triangle, t);
    }
    assert_eq!(f.inner_vertices().count(), f.on_boundary().iter().filter(|b| !**b).count());
}

/// Just inside every edge (a tenth of `h` in, at several places along it), a cross arm is within
/// a few degrees of the edge.
#[test]
fn fields_are_boundary_aligned() {
    for method in [FieldMethod::Smooth, FieldMethod::Distance] {
        for region in [regular(5, 60.0), l_shape(), annulus(), regular(3, 60.0)] {
            let f = field(&region, method, 4.0);
            for (a, b) in region.edges() {
                let d = geometry::sub(b, a);
                let l = geometry::norm(d);
                let n = [-d[1] / l, d[0] / l];
                for s in [0.2, 0.5, 0.8] {
                    let p = geometry::add(geometry::add(a, geometry::scale(d, s)), geometry::scale(n, 0.4));
                    let arm = f.direction(p, d).unwrap();
                    let angle = geometry::cross(arm, d).atan2(geometry::dot(arm, d)).abs().to_degrees();
                    assert!(angle < 3.0, "{method:?} at {p:?}: {angle}°");
                }
            }
        }
    }
}

/// On a disc the distance field's crosses are tangent to circles (and radial), away from the
/// centre, and the divergence of the radial arm is `1/r` (the tangent arm's about 0).
#[test]
fn distance_field_follows_circles_on_a_disc() {
    let f = field(&regular(64, 60.0), FieldMethod::Distance, 4.0);
    for r in [20.0, 35.0, 50.0] {
        let mut mean = 0.0;
        for k in 0..36 {
            let a = k as f64 * 10.0_f64.to_radians() + 0.05;
            let p = [r * a.cos(), r * a.sin()];
            let tangent = [-a.sin(), a.cos()];
            let arm = f.direction(p, tangent).unwrap();
            let angle = geometry::cross(arm, tangent).atan2(geometry::dot(arm, tangent)).abs().to_degrees();
            assert!(angle < 3.0, "at {p:?}: {angle}°");
            // The 64-gon's exact ∇d is constant over 5.6° wedges, so one triangle's divergence
            // is 1/r only on average over the circle.
            let radial = [a.cos(), a.sin()];
            let div = f.divergence(f.locate(p).unwrap(), radial);
            assert!((div * r - 1.0).abs() < 0.4, "div {div} at r = {r}");
            assert!(f.divergence(f.locate(p).unwrap(), tangent).abs() < 0.4 / r);
            mean += div / 36.0;
        }
        assert!((mean * r - 1.0).abs() < 0.05, "mean divergence {mean} at r = {r}");
    }
}

#[test]
fn fields_are_deterministic() {
    for method in [FieldMethod::Smooth, FieldMethod::Distance] {
        let (a, b) = (field(&regular(5, 60.0), method, 4.0), field(&regular(5, 60.0), method, 4.0));
        let bits = |f: &CrossField| f.power().iter().flat_map(|u| u.map(f64::to_bits)).collect::<Vec<_>>();
        assert_eq!(bits(&a), bits(&b));
        assert_eq!(a.singularities(), b.singularities());
        assert_eq!(serde_json::to_string(&field_json(&a)).unwrap(), serde_json::to_string(&field_json(&b)).unwrap());
    }
}

#[test]
fn field_json_has_the_agreed_shape_and_files_are_written() {
    let f = field(&regular(3, 60.0), FieldMethod::Distance, 8.0);
    let text = serde_json::to_string(&field_json(&f)).unwrap();
    assert!(text.starts_with(r#"{"method":"distance","vertices":"#), "{}", &text[..80]);
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(v["vertices"].as_u64(), Some(f.vertices().len() as u64));
    assert_eq!(v["singularities"].as_array().unwrap().len(), 1);
    assert_eq!(v["singularities"][0]["index"].as_f64(), Some(0.25));
    assert_eq!(v["field"]["points"].as_array().unwrap().len(), f.vertices().len());
    assert_eq!(v["field"]["theta"].as_array().unwrap().len(), f.vertices().len());
    assert_eq!(v["field"]["triangles"].as_array().unwrap().len(), f.triangles().len());
    for x in v["field"]["theta"].as_array().unwrap() {
        let x = x.as_f64().unwrap();
        assert_eq!((x * 1e6).round() / 1e6, x);
    }
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    write_field(&out, &f, &[vec![[0.0, 0.0], [10.0, 5.0]]]).unwrap();
    for name in ["field.json", "field.svg", "field.png"] {
        assert!(std::fs::metadata(out.join(name)).unwrap().len() > 100, "{name}");
    }
    assert_eq!(std::fs::read_to_string(out.join("field.json")).unwrap(), text + "\n");
}

#[test]
fn refuses_bad_h() {
    let err = |h: f64| CrossField::new(&square(), &FieldOptions { method: FieldMethod::Smooth, h }).unwrap_err();
    assert!(matches!(err(-1.0), FieldError::Triangulation(cdt::CdtError::BadEdgeLength(_))));
    assert!(matches!(err(0.01), FieldError::Triangulation(cdt::CdtError::TooManyTriangles { .. })));
    let m: FieldMethod = serde_json::from_str("\"distance\"").unwrap();
    assert_eq!((m, serde_json::to_string(&FieldMethod::Smooth).unwrap()), (FieldMethod::Distance, "\"smooth\"".into()));
}

/// The timing note: `cargo test --release --lib layout::field::tests::timing -- --ignored --nocapture`.
#[test]
#[ignore]
fn timing() {
    let region = Polygon::new(vec![[0.0, 0.0], [1000.0, 0.0], [1000.0, 1000.0], [0.0, 1000.0]], vec![]).unwrap();
    let t0 = std::time::Instant::now();
    let mesh = cdt::triangulate(&region, 5.0).unwrap();
    eprintln!(
        "CDT: {} vertices, {} triangles, {:.2} s",
        mesh.vertices.len(),
        mesh.triangles.len(),
        t0.elapsed().as_secs_f64()
    );
    for method in [FieldMethod::Smooth, FieldMethod::Distance] {
        let t0 = std::time::Instant::now();
        let f = field(&region, method, 5.0);
        let t1 = t0.elapsed().as_secs_f64();
        let t2 = std::time::Instant::now();
        let mut found = 0;
        for k in 0..100_000 {
            let p = [(k as f64 * 7.31) % 1000.0, (k as f64 * 3.17) % 1000.0];
            found += f.sample(p).is_some() as usize;
        }
        eprintln!(
            "{method:?}: {} vertices, {} singularities, {t1:.2} s (with CDT); 100k samples {:.3} s ({found} found)",
            f.vertices().len(),
            f.singularities().len(),
            t2.elapsed().as_secs_f64()
        );
    }
}

/// Pictures of every test shape and method in `$NETSPEC_FIELD_PICTURES` (for looking at).
#[test]
#[ignore]
fn pictures() {
    let Some(dir) = std::env::var_os("NETSPEC_FIELD_PICTURES") else { return };
    let shapes = [
        ("square", square()),
        ("l", l_shape()),
        ("triangle", regular(3, 60.0)),
        ("pentagon", regular(5, 60.0)),
        ("disc", regular(64, 60.0)),
        ("annulus", annulus()),
    ];
    for (name, region) in shapes {
        for method in [FieldMethod::Smooth, FieldMethod::Distance] {
            let f = field(&region, method, 4.0);
            write_field(&std::path::Path::new(&dir).join(format!("{name}-{}", method.name())), &f, &[]).unwrap();
        }
    }
}

/// `region` turned by `a` radians about the origin and moved off it.
fn turned(region: &Polygon, a: f64) -> Polygon {
    let (s, c) = a.sin_cos();
    let r =
        |ring: &[P]| ring.iter().map(|q| [c * q[0] - s * q[1] + 3.1, s * q[0] + c * q[1] - 7.3]).collect::<Vec<_>>();
    Polygon::new(r(region.outer()), region.holes().iter().map(|h| r(h)).collect()).unwrap()
}

/// The expected singularity counts of every test shape, turned by each angle and meshed at each
/// `h`, both methods; returns the cases that differ.
fn sweep(angles: &[f64], hs: &[f64]) -> Vec<String> {
    let shapes = [
        ("square", square(), (0, 0)),
        ("L-shape", l_shape(), (0, 0)),
        ("triangle", regular(3, 60.0), (1, 0)),
        ("pentagon", regular(5, 60.0), (0, 1)),
        ("disc", regular(64, 60.0), (4, 0)),
        ("annulus", annulus(), (0, 0)),
    ];
    let mut bad = Vec::new();
    for (name, region, expected) in shapes {
        for &a in angles {
            let region = turned(&region, a);
            for &h in hs {
                for method in [FieldMethod::Smooth, FieldMethod::Distance] {
                    let f = field(&region, method, h);
                    if counts(&f) != expected {
                        bad.push(format!("{name} turned {a}, h = {h}, {method:?}: {:?}", f.singularities()));
                    }
                }
            }
        }
    }
    bad
}

/// The counts do not depend on where the mesh's vertices happen to fall.
#[test]
fn singularity_counts_survive_turning_and_other_h() {
    let bad = sweep(&[0.3, 1.1], &[3.0, 6.0]);
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

/// The same over more angles and edge lengths (2 s; all pass as of writing).
#[test]
#[ignore]
fn singularity_counts_survive_a_wide_sweep() {
    let bad = sweep(&[0.0, 0.3, 1.1], &[1.5, 2.0, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0]);
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

/// Opposite indices in triangles sharing a vertex cancel; apart, or alike, they stay.
#[test]
fn adjacent_opposite_pairs_cancel() {
    let mesh = cdt::triangulate(&square(), 10.0).unwrap();
    let tri = |t: usize| mesh.triangles[t];
    let shares = |a: usize, b: usize| tri(a).iter().any(|v| tri(b).contains(v));
    let near = (1..mesh.triangles.len()).find(|&t| shares(0, t)).unwrap();
    let far = (1..mesh.triangles.len()).find(|&t| !shares(0, t) && !shares(near, t)).unwrap();
    let s = |t: usize, index: f64| Singularity { at: mesh.vertices[tri(t)[0]], index, triangle: t };
    let kept = singular::cancel_pairs(&mesh.triangles, vec![s(0, 0.25), s(near, -0.25), s(far, -0.25)]);
    assert_eq!(kept, vec![s(far, -0.25)]);
    let alike = vec![s(0, 0.25), s(near, 0.25)];
    assert_eq!(singular::cancel_pairs(&mesh.triangles, alike.clone()), alike);
    let apart = vec![s(0, 0.25), s(far, -0.25)];
    assert_eq!(singular::cancel_pairs(&mesh.triangles, apart.clone()), apart);
}

/// Sharper and reflex corners: a five-pointed star (36° tips count 0 quarter turns, 252° notches
/// 3) has one `−1/4`; a quadrilateral with a 114° and a 170° corner around a thin triangular hole
/// (its 22° corner counts 4 quarter turns from the region) has none.
#[test]
fn sharp_and_reflex_corners_follow_poincare_hopf() {
    let star: Vec<P> = (0..10)
        .map(|k| (PI * k as f64 / 5.0 + 0.1, if k % 2 == 0 { 60.0 } else { 25.0 }))
        .map(|(a, r)| [r * a.cos(), r * a.sin()])
        .collect();
    let star = Polygon::new(star, vec![]).unwrap();
    let hole = vec![[90.0, 1.0], [95.0, 1.0], [95.0, 3.0]];
    let holed =
        Polygon::new(vec![[0.0, 0.0], [100.0, 0.0], [100.0, 8.0], [50.0, 30.0], [0.0, 40.0]], vec![hole]).unwrap();
    for (name, region, expected) in [("star", star, (0, 1)), ("holed", holed, (0, 0))] {
        for method in [FieldMethod::Smooth, FieldMethod::Distance] {
            let f = field(&region, method, 4.0);
            let total: f64 = f.singularities().iter().map(|s| s.index).sum();
            assert_eq!(total, poincare_hopf(&region), "{name} {method:?}");
            assert_eq!(counts(&f), expected, "{name} {method:?}: {:?}", f.singularities());
        }
    }
}
