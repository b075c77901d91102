//! Welding coincident vertices within a tolerance.

use super::Mesh;

/// The result of welding: the mesh on merged vertices and the maps between numberings.
#[derive(Debug, Clone)]
pub struct Welded {
    /// The mesh with merged vertices (triangles renumbered).
    pub mesh: Mesh,
    /// For each original vertex, its merged vertex.
    pub to_merged: Vec<u32>,
    /// For each merged vertex, the smallest original vertex merged into it.
    pub representative: Vec<u32>,
}

/// Merges vertices closer than `tolerance` (Euclidean; chains merge transitively).
pub fn weld(mesh: &Mesh, tolerance: f64) -> Welded {
    let n = mesh.positions.len();
    let mut parent: Vec<u32> = (0..n as u32).collect();
    fn find(p: &mut [u32], mut i: u32) -> u32 {
        while p[i as usize] != i {
            p[i as usize] = p[p[i as usize] as usize];
            i = p[i as usize];
        }
        i
    }
    // Sweep along x: only points within `tolerance` in x can merge.
    let mut order: Vec<u32> = (0..n as u32).collect();
    order.sort_by(|&a, &b| {
        mesh.positions[a as usize]
            .x
            .total_cmp(&mesh.positions[b as usize].x)
    });
    let tol2 = tolerance * tolerance;
    for (k, &i) in order.iter().enumerate() {
        let p = mesh.positions[i as usize];
        for &j in &order[k + 1..] {
            let q = mesh.positions[j as usize];
            if q.x - p.x > tolerance {
                break;
            }
            if p.distance_squared(q) <= tol2 {
                let (ri, rj) = (find(&mut parent, i), find(&mut parent, j));
                if ri != rj {
                    // Keep the smaller original index as the root.
                    let (lo, hi) = (ri.min(rj), ri.max(rj));
                    parent[hi as usize] = lo;
                }
            }
        }
    }
    let mut to_merged = vec![u32::MAX; n];
    let mut representative = Vec::new();
    let mut positions = Vec::new();
    for i in 0..n as u32 {
        let r = find(&mut parent, i);
        if to_merged[r as usize] == u32::MAX {
            to_merged[r as usize] = representative.len() as u32;
            representative.push(r);
            positions.push(mesh.positions[r as usize]);
        }
        to_merged[i as usize] = to_merged[r as usize];
    }
    let triangles = mesh
        .triangles
        .iter()
        .map(|t| t.map(|i| to_merged[i as usize]))
        .collect();
    Welded {
        mesh: Mesh {
            positions,
            triangles,
        },
        to_merged,
        representative,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn merges_within_tolerance_and_keeps_smallest_index() {
        let mesh = Mesh {
            positions: vec![
                DVec3::ZERO,
                DVec3::X,
                DVec3::new(1.0 + 1e-9, 0.0, 0.0),
                DVec3::Y,
                DVec3::new(0.0, 1.0, 1e-3),
            ],
            triangles: vec![[0, 1, 3], [0, 2, 4]],
        };
        let w = weld(&mesh, 1e-6);
        assert_eq!(w.mesh.positions.len(), 4);
        assert_eq!(w.representative, vec![0, 1, 3, 4]);
        assert_eq!(w.mesh.triangles, vec![[0, 1, 2], [0, 1, 3]]);
        assert_eq!(w.to_merged[2], 1);
    }
}
