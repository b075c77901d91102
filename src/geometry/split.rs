//! Conforming edge splitting: every edge longer than a length is halved, in every triangle
//! that has it (the midpoint is shared), until none is — so the refined mesh has no
//! T-junctions and no cracks, covers exactly the same surface, and keeps its winding.
//! For views that move vertices nonlinearly (the stereographic visibility map projects
//! only vertices, so a long edge would bend wrongly).

use std::collections::HashMap;

use super::Mesh;

/// The most rounds of halving (each round at least halves the longest edge).
const MAX_ROUNDS: usize = 40;

/// `mesh` with every edge longer than `max_len` halved (repeatedly, conformingly).
pub fn split_long_edges(mesh: &Mesh, max_len: f64) -> Mesh {
    let mut out = mesh.clone();
    if !(max_len.is_finite() && max_len > 0.0) {
        return out;
    }
    for _ in 0..MAX_ROUNDS {
        let long = |out: &Mesh, a: u32, b: u32| {
            out.positions[a as usize].distance(out.positions[b as usize]) > max_len
        };
        if !out
            .triangles
            .iter()
            .any(|&[a, b, c]| long(&out, a, b) || long(&out, b, c) || long(&out, c, a))
        {
            break;
        }
        let mut midpoints: HashMap<(u32, u32), u32> = HashMap::new();
        let mut triangles = Vec::with_capacity(out.triangles.len() * 2);
        let old = std::mem::take(&mut out.triangles);
        for [a, b, c] in old {
            let mut mid = |p: u32, q: u32, out: &mut Mesh| -> Option<u32> {
                if !long(out, p, q) {
                    return None;
                }
                let key = (p.min(q), p.max(q));
                Some(*midpoints.entry(key).or_insert_with(|| {
                    let m = (out.positions[p as usize] + out.positions[q as usize]) * 0.5;
                    out.positions.push(m);
                    (out.positions.len() - 1) as u32
                }))
            };
            let (ab, bc, ca) = (
                mid(a, b, &mut out),
                mid(b, c, &mut out),
                mid(c, a, &mut out),
            );
            triangles.extend(split_triangle([a, b, c], [ab, bc, ca]));
        }
        out.triangles = triangles;
    }
    out
}

/// Triangle a, b, c with the midpoints of ab, bc, ca where they are split, as the
/// triangles that cover it (same winding).
fn split_triangle([a, b, c]: [u32; 3], mids: [Option<u32>; 3]) -> Vec<[u32; 3]> {
    match mids {
        [None, None, None] => vec![[a, b, c]],
        [Some(ab), Some(bc), Some(ca)] => {
            vec![[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]
        }
        // One or two edges split: rotate so the first split edge is ab, then fan.
        [Some(ab), None, None] => vec![[a, ab, c], [ab, b, c]],
        [None, Some(_), None] => split_triangle([b, c, a], [mids[1], None, None]),
        [None, None, Some(_)] => split_triangle([c, a, b], [mids[2], None, None]),
        [Some(ab), Some(bc), None] => vec![[a, ab, c], [ab, b, bc], [ab, bc, c]],
        [None, Some(_), Some(_)] => split_triangle([b, c, a], [mids[1], mids[2], None]),
        [Some(_), None, Some(_)] => split_triangle([c, a, b], [mids[2], mids[0], None]),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn area(m: &Mesh) -> DVec3 {
        (0..m.triangles.len()).map(|t| m.face_normal(t) * 0.5).sum()
    }

    #[test]
    fn long_edges_are_halved_conformingly_and_the_surface_is_kept() {
        // Two triangles of a 4 × 1 quad: only the long edges (and the diagonal) split.
        let quad = Mesh {
            positions: vec![
                DVec3::new(0.0, 0.0, 0.0),
                DVec3::new(4.0, 0.0, 0.0),
                DVec3::new(4.0, 1.0, 0.0),
                DVec3::new(0.0, 1.0, 0.0),
            ],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
        };
        let split = split_long_edges(&quad, 1.1);
        for &[a, b, c] in &split.triangles {
            for (p, q) in [(a, b), (b, c), (c, a)] {
                let d = split.positions[p as usize].distance(split.positions[q as usize]);
                assert!(d <= 1.1, "{d}");
            }
        }
        // The same oriented area (winding kept, nothing lost or doubled).
        assert!((area(&split) - area(&quad)).length() < 1e-12);
        assert!((area(&split).z - 4.0).abs() < 1e-12);
        // Conforming: every interior edge is shared by exactly two triangles, in opposite
        // directions; the border is the quad's outline, 10 unit-ish segments.
        let mut directed: HashMap<(u32, u32), i32> = HashMap::new();
        for &[a, b, c] in &split.triangles {
            for (p, q) in [(a, b), (b, c), (c, a)] {
                *directed.entry((p, q)).or_default() += 1;
            }
        }
        let border = directed
            .keys()
            .filter(|(p, q)| !directed.contains_key(&(*q, *p)))
            .count();
        assert!(directed.values().all(|&n| n == 1));
        assert_eq!(border, 10);
        // Short edges stay whole.
        assert_eq!(split_long_edges(&quad, 10.0).triangles, quad.triangles);
    }
}
