//! Procedural meshes for tests and benchmarks: a torus, a bumpy open surface (scan-like),
//! boxes and a detailed building, all counter-clockwise with outward normals.

use glam::DVec3;

use super::Mesh;

/// A tiny deterministic pseudo-random generator (xorshift64) for procedural data, tests
/// and benchmarks: not for anything that needs real randomness.
#[derive(Debug, Clone)]
pub struct XorShift(u64);

impl XorShift {
    /// A generator from a seed (0 is replaced by 1).
    pub fn new(seed: u64) -> XorShift {
        XorShift(seed.max(1))
    }

    /// The next value, uniform in [0, 1).
    pub fn next_f64(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A torus around +Z: `major` segments around, `minor` segments across.
pub fn torus(major: u32, minor: u32, r_major: f64, r_minor: f64) -> Mesh {
    let mut m = Mesh::default();
    for i in 0..major {
        let u = i as f64 / major as f64 * std::f64::consts::TAU;
        for j in 0..minor {
            let v = j as f64 / minor as f64 * std::f64::consts::TAU;
            let r = r_major + r_minor * v.cos();
            m.positions
                .push(DVec3::new(r * u.cos(), r * u.sin(), r_minor * v.sin()));
        }
    }
    let id = |i: u32, j: u32| (i % major) * minor + (j % minor);
    for i in 0..major {
        for j in 0..minor {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            m.triangles.push([a, b, c]);
            m.triangles.push([a, c, d]);
        }
    }
    m
}

/// A height field over [0, size]² with `n` × `n` quads: an open surface with border edges,
/// bumpy like a scan (sums of sines with a deterministic pseudo-random jitter).
pub fn bumpy_surface(n: u32, size: f64, seed: u64) -> Mesh {
    let mut m = Mesh::default();
    let mut rng = XorShift::new(seed);
    let mut rnd = move || rng.next_f64() - 0.5;
    for i in 0..=n {
        for j in 0..=n {
            let (x, y) = (i as f64 / n as f64 * size, j as f64 / n as f64 * size);
            let z = 0.08 * size * ((x * 3.1 / size).sin() * (y * 2.3 / size).cos())
                + 0.02 * size * ((x * 17.0 / size).sin() + (y * 13.0 / size).sin())
                + 0.002 * size * rnd();
            m.positions.push(DVec3::new(x, y, z));
        }
    }
    let id = |i: u32, j: u32| i * (n + 1) + j;
    for i in 0..n {
        for j in 0..n {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            m.triangles.push([a, b, c]);
            m.triangles.push([a, c, d]);
        }
    }
    m
}

/// Appends an axis-aligned box (12 triangles, its own 8 vertices).
pub fn push_box(m: &mut Mesh, lo: DVec3, hi: DVec3) {
    let base = m.positions.len() as u32;
    for k in 0..8 {
        m.positions.push(DVec3::new(
            if k & 1 == 0 { lo.x } else { hi.x },
            if k & 2 == 0 { lo.y } else { hi.y },
            if k & 4 == 0 { lo.z } else { hi.z },
        ));
    }
    const FACES: [[u32; 4]; 6] = [
        [0, 2, 3, 1], // −z
        [4, 5, 7, 6], // +z
        [0, 1, 5, 4], // −y
        [2, 6, 7, 3], // +y
        [0, 4, 6, 2], // −x
        [1, 3, 7, 5], // +x
    ];
    for f in FACES {
        let [a, b, c, d] = f.map(|i| base + i);
        m.triangles.push([a, b, c]);
        m.triangles.push([a, c, d]);
    }
}

/// A box mesh.
pub fn cuboid(lo: DVec3, hi: DVec3) -> Mesh {
    let mut m = Mesh::default();
    push_box(&mut m, lo, hi);
    m
}

/// A "detailed building": `nx` × `ny` bays of `floors` storeys, each storey a slab and a
/// set-back window band with mullions — many small closed boxes, about
/// 12 · nx · ny · floors · 4 triangles.
pub fn building(nx: u32, ny: u32, floors: u32) -> Mesh {
    let mut m = Mesh::default();
    let (bay, storey) = (3.0, 3.2);
    for i in 0..nx {
        for j in 0..ny {
            let (x0, y0) = (i as f64 * bay, j as f64 * bay);
            for f in 0..floors {
                let z0 = f as f64 * storey;
                push_box(
                    &mut m,
                    DVec3::new(x0, y0, z0),
                    DVec3::new(x0 + bay, y0 + bay, z0 + 0.4),
                );
                let inset = 0.25;
                push_box(
                    &mut m,
                    DVec3::new(x0 + inset, y0 + inset, z0 + 0.4),
                    DVec3::new(x0 + bay - inset, y0 + bay - inset, z0 + storey),
                );
                // Two mullions on the outer faces.
                push_box(
                    &mut m,
                    DVec3::new(x0, y0, z0 + 0.4),
                    DVec3::new(x0 + 0.2, y0 + 0.2, z0 + storey),
                );
                push_box(
                    &mut m,
                    DVec3::new(x0 + bay - 0.2, y0 + bay - 0.2, z0 + 0.4),
                    DVec3::new(x0 + bay, y0 + bay, z0 + storey),
                );
            }
        }
    }
    m
}

/// Appends a closed beam of square cross-section `thickness` from `a` to `b` (12 triangles).
pub fn push_beam(m: &mut Mesh, a: DVec3, b: DVec3, thickness: f64) {
    let axis = (b - a).normalize();
    let u = axis.any_orthonormal_vector() * (thickness / 2.0);
    let v = axis.cross(u);
    let base = m.positions.len() as u32;
    for end in [a, b] {
        for (su, sv) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            m.positions.push(end + u * su + v * sv);
        }
    }
    // Ring k at `a` is k, at `b` is k + 4; (u, v, axis) is right-handed.
    let mut quad = |q: [u32; 4]| {
        let [p, q1, r, s] = q.map(|i| base + i);
        m.triangles.push([p, q1, r]);
        m.triangles.push([p, r, s]);
    };
    quad([0, 3, 2, 1]);
    quad([4, 5, 6, 7]);
    for k in 0..4 {
        let n = (k + 1) % 4;
        quad([k, n, n + 4, k + 4]);
    }
}

/// Appends a closed sawtooth roof tooth over x ∈ [x0, x1], y ∈ [y0, y1] from height `z`:
/// a wedge whose vertical face (the north light) is at x1, `rise` metres high.
pub fn push_tooth(m: &mut Mesh, x0: f64, x1: f64, y0: f64, y1: f64, z: f64, rise: f64) {
    let base = m.positions.len() as u32;
    for y in [y0, y1] {
        m.positions.push(DVec3::new(x0, y, z));
        m.positions.push(DVec3::new(x1, y, z));
        m.positions.push(DVec3::new(x1, y, z + rise));
    }
    let t = |a: u32, b: u32, c: u32| [base + a, base + b, base + c];
    m.triangles.extend([
        t(0, 2, 1),
        t(3, 4, 5),
        t(0, 1, 4),
        t(0, 4, 3),
        t(1, 2, 5),
        t(1, 5, 4),
        t(0, 3, 5),
        t(0, 5, 2),
    ]);
}

/// A small industrial area for shadow studies (Wallner Figs. 1.5–1.7): a sawtooth-roofed
/// hall, a flat warehouse, an office block of storeys and a 40 m lattice tower, about
/// 1 800 triangles, +Z up, the ground at z = 0.
pub fn industrial_area() -> Mesh {
    let mut m = Mesh::default();
    // Hall with a sawtooth roof: 40 × 20 × 7 m, eight teeth 2.5 m high.
    push_box(
        &mut m,
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(40.0, 20.0, 7.0),
    );
    for k in 0..8 {
        let x0 = k as f64 * 5.0;
        push_tooth(&mut m, x0, x0 + 5.0, 0.0, 20.0, 7.0, 2.5);
    }
    // Warehouse: 25 × 14 × 9 m.
    push_box(
        &mut m,
        DVec3::new(48.0, 4.0, 0.0),
        DVec3::new(73.0, 18.0, 9.0),
    );
    // Office block: 4 × 3 bays of 3 m, 6 storeys, beside the hall.
    let mut office = building(4, 3, 6);
    for p in &mut office.positions {
        *p += DVec3::new(5.0, 28.0, 0.0);
    }
    let base = m.positions.len() as u32;
    m.positions.extend(office.positions);
    m.triangles
        .extend(office.triangles.iter().map(|t| t.map(|i| i + base)));
    // Lattice tower: four legs tapering from 6 m to 2 m apart over 40 m, braced every 4 m.
    let centre = DVec3::new(62.0, 32.0, 0.0);
    let leg = |corner: usize, z: f64| {
        let half = 3.0 - 2.0 * z / 40.0;
        let (sx, sy) = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)][corner];
        centre + DVec3::new(sx * half, sy * half, z)
    };
    for c in 0..4 {
        push_beam(&mut m, leg(c, 0.0), leg(c, 40.0), 0.35);
    }
    for level in 0..10 {
        let (z0, z1) = (level as f64 * 4.0, level as f64 * 4.0 + 4.0);
        for c in 0..4 {
            let n = (c + 1) % 4;
            push_beam(&mut m, leg(c, z1), leg(n, z1), 0.15);
            push_beam(&mut m, leg(c, z0), leg(n, z1), 0.12);
        }
    }
    m
}

/// The same surface as CAD exporters tessellate it: every triangle of `mesh` split into
/// `strips` long thin triangles, fanned from its first corner to points evenly along the
/// opposite edge. Area, orientation and outline are unchanged; shared edges gain
/// T-vertices as they do in real CAD exports.
pub fn fan_split(mesh: &Mesh, strips: u32) -> Mesh {
    let strips = strips.max(1);
    let mut out = Mesh::default();
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
        let apex = out.positions.len() as u32;
        out.positions.push(a);
        for k in 0..=strips {
            out.positions.push(b + (c - b) * (k as f64 / strips as f64));
        }
        for k in 0..strips {
            out.triangles.push([apex, apex + 1 + k, apex + 2 + k]);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fan_split_keeps_area_and_orientation() {
        let mesh = cuboid(DVec3::ZERO, DVec3::new(2.0, 1.0, 0.5));
        let split = fan_split(&mesh, 50);
        assert_eq!(split.triangles.len(), 50 * mesh.triangles.len());
        let area = |m: &Mesh| -> f64 {
            (0..m.triangles.len())
                .map(|t| m.face_normal(t).length() / 2.0)
                .sum()
        };
        assert!((area(&split) - area(&mesh)).abs() < 1e-12 * area(&mesh));
        // Each piece faces the way its triangle does.
        for (t, _) in mesh.triangles.iter().enumerate() {
            let n = mesh.face_normal(t).normalize();
            for k in 0..50 {
                let m = split.face_normal(50 * t + k).normalize();
                assert!((m - n).length() < 1e-9);
            }
        }
    }
}
