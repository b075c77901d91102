//! Writes the bundled scenes' models and textures in `assets/scenes/` and the effect
//! light's distribution `luminaires/effects/disco.ldt`:
//! `cargo run --example make_scenes`. Everything is procedural, so the output is ours.
//! `cargo run --release --example make_scenes -- cad-office DIR` writes only the large
//! CAD-like office (256 200 long thin triangles, 17 MB, not bundled) into DIR.

use std::fmt::Write as _;
use std::path::Path;

use glam::DVec3;
use goniolight::photometry::eulumdat::{Dimensions, Eulumdat, LampSet};
use goniolight::photometry::Symmetry;

/// An OBJ being written: boxes and quads in metres, Z up, per-face normals and UVs.
#[derive(Default)]
struct Obj {
    text: String,
    v: usize,
    vt: usize,
    vn: usize,
}

impl Obj {
    fn object(&mut self, name: &str, material: &str) {
        let _ = writeln!(self.text, "o {name}\nusemtl {material}");
    }

    /// A quad a, b, c, d (counter-clockwise seen from its front); UVs in metres/`tile`.
    fn quad(&mut self, p: [DVec3; 4], tile: f64) {
        let n = (p[1] - p[0]).cross(p[3] - p[0]).normalize();
        let u_axis = (p[1] - p[0]).normalize();
        let v_axis = n.cross(u_axis);
        for q in p {
            let d = q - p[0];
            let _ = writeln!(self.text, "v {:.4} {:.4} {:.4}", q.x, q.y, q.z);
            let _ = writeln!(
                self.text,
                "vt {:.4} {:.4}",
                d.dot(u_axis) / tile,
                d.dot(v_axis) / tile
            );
        }
        let _ = writeln!(self.text, "vn {:.4} {:.4} {:.4}", n.x, n.y, n.z);
        self.vn += 1;
        let (v, t, n) = (self.v, self.vt, self.vn);
        let c = |k: usize| format!("{}/{}/{}", v + k, t + k, n);
        let _ = writeln!(self.text, "f {} {} {} {}", c(1), c(2), c(3), c(4));
        self.v += 4;
        self.vt += 4;
    }

    /// An axis-aligned box with outward faces.
    fn cuboid(&mut self, lo: DVec3, hi: DVec3) {
        for q in box_quads(lo, hi) {
            self.quad(q, 1.0);
        }
    }

    /// A box standing on the floor: outward faces but no bottom.
    fn open_box(&mut self, lo: DVec3, hi: DVec3) {
        for (k, q) in box_quads(lo, hi).into_iter().enumerate() {
            if k != 1 {
                self.quad(q, 1.0);
            }
        }
    }

    /// A horizontal `x` × `y` rectangle from the origin at height `z`, facing up (a floor)
    /// or down (a ceiling).
    fn level(&mut self, x: f64, y: f64, z: f64, up: bool) {
        let p = |x: f64, y: f64| DVec3::new(x, y, z);
        let corners = if up {
            [p(0.0, 0.0), p(x, 0.0), p(x, y), p(0.0, y)]
        } else {
            [p(0.0, y), p(x, y), p(x, 0.0), p(0.0, 0.0)]
        };
        self.quad(corners, 1.0);
    }

    /// The inside of a room `size` (floor at z = 0), faces pointing inward.
    fn room(&mut self, size: DVec3, floor: &str, wall: &str, feature_wall: &str, ceiling: &str) {
        let (x, y, z) = (size.x, size.y, size.z);
        self.object("floor", floor);
        self.level(x, y, 0.0, true);
        self.object("ceiling", ceiling);
        self.level(x, y, z, false);
        self.object("walls", wall);
        self.wall((x, 0.0), (0.0, 0.0), z);
        self.wall((0.0, 0.0), (0.0, y), z);
        self.wall((x, y), (x, 0.0), z);
        self.object("back_wall", feature_wall);
        self.wall((0.0, y), (x, y), z);
    }

    /// A vertical wall from plan point `a` to `b`, floor to `z`, facing left of a → b.
    fn wall(&mut self, (ax, ay): (f64, f64), (bx, by): (f64, f64), z: f64) {
        let p = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
        self.quad(
            [p(ax, ay, 0.0), p(bx, by, 0.0), p(bx, by, z), p(ax, ay, z)],
            1.0,
        );
    }

    fn write(&self, path: &Path, mtl: &str) -> std::io::Result<()> {
        let header = format!(
            "# goniolight bundled scene geometry (metres, Z up), written by examples/make_scenes.rs\nmtllib {mtl}\n"
        );
        std::fs::write(path, header + &self.text)
    }

    /// Writes `dir/name.obj` and its materials, `materials`, as `dir/name.mtl`.
    fn write_with_mtl(&self, dir: &Path, name: &str, materials: &str) -> std::io::Result<()> {
        self.write(&dir.join(format!("{name}.obj")), &format!("{name}.mtl"))?;
        std::fs::write(dir.join(format!("{name}.mtl")), materials)
    }
}

/// The six faces of an axis-aligned box, counter-clockwise from outside: top, bottom,
/// then the sides at y = lo, y = hi, x = lo and x = hi.
fn box_quads(a: DVec3, b: DVec3) -> [[DVec3; 4]; 6] {
    let p = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
    [
        [
            p(a.x, a.y, b.z),
            p(b.x, a.y, b.z),
            p(b.x, b.y, b.z),
            p(a.x, b.y, b.z),
        ],
        [
            p(a.x, b.y, a.z),
            p(b.x, b.y, a.z),
            p(b.x, a.y, a.z),
            p(a.x, a.y, a.z),
        ],
        [
            p(a.x, a.y, a.z),
            p(b.x, a.y, a.z),
            p(b.x, a.y, b.z),
            p(a.x, a.y, b.z),
        ],
        [
            p(b.x, b.y, a.z),
            p(a.x, b.y, a.z),
            p(a.x, b.y, b.z),
            p(b.x, b.y, b.z),
        ],
        [
            p(a.x, b.y, a.z),
            p(a.x, a.y, a.z),
            p(a.x, a.y, b.z),
            p(a.x, b.y, b.z),
        ],
        [
            p(b.x, a.y, a.z),
            p(b.x, b.y, a.z),
            p(b.x, b.y, b.z),
            p(b.x, a.y, b.z),
        ],
    ]
}

/// The box room with four boxes of furniture on its floor: 52 triangles (each box
/// without its bottom), the case Edström's face clusters are for when tessellated finely.
fn boxes_room(size: DVec3) -> Obj {
    let mut o = Obj::default();
    o.room(size, "floor", "wall", "wall", "ceiling");
    for (k, (lo, hi)) in [
        ([0.5, 0.5, 0.0], [2.0, 1.3, 0.75]),
        ([4.0, 0.4, 0.0], [5.5, 1.0, 0.9]),
        ([1.0, 2.8, 0.0], [1.8, 3.6, 1.8]),
        ([3.5, 2.2, 0.0], [4.7, 3.2, 0.45]),
    ]
    .into_iter()
    .enumerate()
    {
        o.object(&format!("box{k}"), "furniture");
        o.open_box(DVec3::from_array(lo), DVec3::from_array(hi));
    }
    o
}

/// An open-plan office of 24 × 16 × 3 m: 48 desks (1.6 × 0.8 × 0.75 m) in six rows and 24
/// cabinets (0.8 × 0.45 × 1.2 m) along the long walls, as boxes without bottoms.
fn office() -> Obj {
    let mut o = Obj::default();
    o.room(
        DVec3::new(24.0, 16.0, 3.0),
        "floor",
        "wall",
        "wall",
        "ceiling",
    );
    let mut k = 0;
    for row in 0..6 {
        for col in 0..8 {
            let lo = DVec3::new(1.5 + 2.8 * col as f64, 2.0 + 2.2 * row as f64, 0.0);
            o.object(&format!("desk{k}"), "furniture");
            o.open_box(lo, lo + DVec3::new(1.6, 0.8, 0.75));
            k += 1;
        }
    }
    for side in 0..2 {
        for n in 0..12 {
            let y = if side == 0 { 0.05 } else { 15.5 };
            let lo = DVec3::new(0.8 + 1.9 * n as f64, y, 0.0);
            o.object(&format!("cabinet{side}_{n}"), "furniture");
            o.open_box(lo, lo + DVec3::new(0.8, 0.45, 1.2));
        }
    }
    o
}

/// The scene file of the CAD-like office (`dir`: where it is written; luminaires by
/// absolute path into this repository).
fn office_toml(root: &Path) -> String {
    let ldt = root.join("luminaires/eulumdat-plot/sample_06_isym1.ldt");
    let mut text = String::from(
        "# An open-plan office (24 × 16 × 3 m, 48 desks, 24 cabinets; reflectances 0.2 floor,\n\
         # 0.5 walls, 0.7 ceiling, 0.4 furniture) drawn as CAD exporters do: every face fanned\n\
         # into long thin strips. Written by `cargo run --release --example make_scenes --\n\
         # cad-office DIR`; the large radiosity benchmark of Edström's face clusters.\n\n\
         [[model]]\npath = \"cad_office.obj\"\nup = \"z\"\n",
    );
    for j in 0..3 {
        for i in 0..4 {
            let _ = write!(
                text,
                "\n[[luminaire]]\nfile = {:?}\nposition = [{:.1}, {:.1}, 2.95]\n",
                ldt.display().to_string(),
                3.0 + 6.0 * i as f64,
                2.7 + 5.3 * j as f64,
            );
        }
    }
    text.push_str(
        "\n[camera]\nposition = [0.5, 0.5, 1.6]\nlook_at = [12.0, 8.0, 0.8]\nfov_deg = 70.0\n\n[display]\nmode = \"illuminance\"\n",
    );
    text
}

/// Writes `scene`'s triangles to `obj`, each fanned into `strips` long thin strips as CAD
/// exporters do, with its material from `mtl`; returns the triangles and the strips.
fn write_fanned(
    scene: &goniolight::scene::Scene,
    strips: u32,
    obj: &Path,
    mtl: &str,
) -> anyhow::Result<(goniolight::geometry::Mesh, goniolight::geometry::Mesh)> {
    let coarse = scene.caster_mesh();
    let fine = goniolight::geometry::generate::fan_split(&coarse, strips);
    let materials: Vec<(usize, String)> = scene
        .caster_materials()
        .into_iter()
        .flat_map(|m| std::iter::repeat_n((m, scene.materials[m].name.clone()), strips as usize))
        .collect();
    std::fs::write(obj, triangles_obj(&fine, &materials, mtl))?;
    Ok((coarse, fine))
}

/// Writes the CAD-like office (≥ 250 000 long thin triangles) into `dir`: the coarse
/// boxes fanned into `strips` strips each.
fn cad_office(root: &Path, dir: &Path, strips: u32) -> anyhow::Result<()> {
    std::fs::create_dir_all(dir)?;
    office().write_with_mtl(dir, "cad_office", &format!("{ROOM_MTL}{FURNITURE_MTL}"))?;
    std::fs::write(dir.join("cad_office.toml"), office_toml(root))?;
    let scene = goniolight::scene::Scene::load(&dir.join("cad_office.toml"))?;
    let (coarse, fine) = write_fanned(
        &scene,
        strips,
        &dir.join("cad_office.obj"),
        "cad_office.mtl",
    )?;
    println!(
        "wrote {} ({} triangles from {} faces' {} triangles, {strips} strips each)",
        dir.join("cad_office.toml").display(),
        fine.triangles.len(),
        coarse.triangles.len() / 2,
        coarse.triangles.len(),
    );
    Ok(())
}

/// `mesh` (triangles of one material each, `materials`) as an OBJ with `usemtl` groups.
fn triangles_obj(
    mesh: &goniolight::geometry::Mesh,
    materials: &[(usize, String)],
    mtl: &str,
) -> String {
    let mut text = format!(
        "# goniolight CAD-like scene geometry (metres, Z up), written by examples/make_scenes.rs\nmtllib {mtl}\n"
    );
    for p in &mesh.positions {
        let _ = writeln!(text, "v {:.6} {:.6} {:.6}", p.x, p.y, p.z);
    }
    let mut current = None;
    for (t, (m, name)) in mesh.triangles.iter().zip(materials) {
        if current != Some(*m) {
            current = Some(*m);
            let _ = writeln!(text, "usemtl {name}");
        }
        let _ = writeln!(text, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1);
    }
    text
}

fn furniture(o: &mut Obj) {
    let b = |o: &mut Obj, name: &str, mat: &str, lo: [f64; 3], hi: [f64; 3]| {
        o.object(name, mat);
        o.cuboid(DVec3::from_array(lo), DVec3::from_array(hi));
    };
    // Dining table with four legs.
    b(o, "table_top", "oak", [2.2, 1.4, 0.71], [3.8, 2.3, 0.75]);
    for (x, y) in [(2.25, 1.45), (3.7, 1.45), (2.25, 2.2), (3.7, 2.2)] {
        b(
            o,
            "table_leg",
            "oak",
            [x, y, 0.0],
            [x + 0.05, y + 0.05, 0.71],
        );
    }
    // Two chairs.
    for (x, y, back_y) in [(2.6, 0.95, 0.95), (3.0, 2.5, 2.9)] {
        b(
            o,
            "chair_seat",
            "fabric",
            [x, y, 0.44],
            [x + 0.45, y + 0.45, 0.48],
        );
        b(
            o,
            "chair_back",
            "fabric",
            [x, back_y, 0.48],
            [x + 0.45, back_y + 0.05, 0.95],
        );
        for (dx, dy) in [(0.0, 0.0), (0.4, 0.0), (0.0, 0.4), (0.4, 0.4)] {
            b(
                o,
                "chair_leg",
                "metal",
                [x + dx, y + dy, 0.0],
                [x + dx + 0.04, y + dy + 0.04, 0.44],
            );
        }
    }
    // Desk in the corner, with the desk lamp's base and arm.
    b(o, "desk", "oak", [4.6, 0.1, 0.72], [5.9, 0.8, 0.75]);
    b(o, "desk_side", "oak", [4.6, 0.1, 0.0], [4.64, 0.8, 0.72]);
    b(o, "desk_side", "oak", [5.86, 0.1, 0.0], [5.9, 0.8, 0.72]);
    b(
        o,
        "lamp_base",
        "metal",
        [5.55, 0.15, 0.75],
        [5.7, 0.3, 0.78],
    );
    b(
        o,
        "lamp_post",
        "metal",
        [5.61, 0.21, 0.78],
        [5.64, 0.24, 1.2],
    );
    b(
        o,
        "lamp_head",
        "metal",
        [5.2, 0.18, 1.2],
        [5.66, 0.28, 1.24],
    );
    // Bookshelf against the left wall.
    b(o, "shelf_side", "oak", [0.05, 0.6, 0.0], [0.4, 0.63, 2.0]);
    b(o, "shelf_side", "oak", [0.05, 1.77, 0.0], [0.4, 1.8, 2.0]);
    for k in 0..5 {
        let z = 0.05 + k as f64 * 0.48;
        b(
            o,
            "shelf_board",
            "oak",
            [0.05, 0.63, z],
            [0.4, 1.77, z + 0.03],
        );
    }
    // Sofa under the picture.
    b(o, "sofa_seat", "fabric", [1.0, 3.1, 0.0], [2.8, 3.9, 0.45]);
    b(
        o,
        "sofa_back",
        "fabric",
        [1.0, 3.75, 0.45],
        [2.8, 3.95, 0.85],
    );
    b(o, "sofa_arm", "fabric", [0.9, 3.1, 0.0], [1.05, 3.95, 0.65]);
    b(o, "sofa_arm", "fabric", [2.75, 3.1, 0.0], [2.9, 3.95, 0.65]);
    // Pictures on the back wall, lit by the wall spots.
    b(o, "picture", "canvas", [1.4, 3.97, 1.2], [2.4, 3.995, 1.9]);
    b(
        o,
        "picture",
        "canvas_dark",
        [4.0, 3.97, 1.1],
        [5.0, 3.995, 1.8],
    );
    // The downlights' housings (just below the ceiling, above their photometric centres).
    for (x, y) in [(2.0, 1.85), (4.0, 1.85)] {
        b(
            o,
            "downlight",
            "metal",
            [x - 0.1, y - 0.1, 2.96],
            [x + 0.1, y + 0.1, 3.0],
        );
    }
}

const ROOM_MTL: &str = "# Diffuse reflectances (Kd) as in the radiosity validation room:
# floor 0.2, walls 0.5, ceiling 0.7.
newmtl floor
Kd 0.2 0.2 0.2
newmtl wall
Kd 0.5 0.5 0.5
newmtl ceiling
Kd 0.7 0.7 0.7
";

/// A 4 × 4 × 3 m room whose ceiling is a translucent panel at 2.6 m, wall to wall, with
/// a plenum above it (its walls a material of their own, so no chart spans the panel's
/// plane): the diffuse-transmission validation room.
fn luminous_ceiling() -> Obj {
    let (x, y, z, panel) = (4.0, 4.0, 3.0, 2.6);
    let p = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
    let mut o = Obj::default();
    o.object("floor", "floor");
    o.level(x, y, 0.0, true);
    o.object("ceiling", "ceiling");
    o.level(x, y, z, false);
    o.object("panel", "opal");
    o.level(x, y, panel, false);
    for (name, material, lo, hi) in [
        ("walls", "wall", 0.0, panel),
        ("plenum", "plenum", panel, z),
    ] {
        o.object(name, material);
        let corners = [
            p(0.0, 0.0, 0.0),
            p(x, 0.0, 0.0),
            p(x, y, 0.0),
            p(0.0, y, 0.0),
        ];
        for k in 0..4 {
            let (a, b) = (corners[(k + 1) % 4], corners[k]);
            o.quad(
                [
                    a + p(0.0, 0.0, lo),
                    b + p(0.0, 0.0, lo),
                    b + p(0.0, 0.0, hi),
                    a + p(0.0, 0.0, hi),
                ],
                1.0,
            );
        }
    }
    o
}

/// The luminous ceiling's panel and plenum walls; the rest of its materials are
/// [`ROOM_MTL`]'s. The panel's transmittance is set in its scene file.
const LUMINOUS_CEILING_MTL: &str = "newmtl opal
Kd 0.4 0.4 0.4
newmtl plenum
Kd 0.5 0.5 0.5
";

/// The mirror room's mirror: no diffuse part (its reflectance is set in its scene file).
const MIRROR_MTL: &str = "newmtl mirror
Kd 0 0 0
";

/// The glass partition's pane: no diffuse part (its transmittance is set in its scene
/// file).
const GLASS_MTL: &str = "newmtl glass
Kd 0 0 0
";

/// A 6 × 4 × 3 m room split at x = 3 by a pane of clear glass, wall to wall and floor to
/// ceiling: each half's floor, ceiling and walls are surfaces of their own, so no chart
/// spans the pane's plane. The glass-partition validation room.
fn glass_partition() -> Obj {
    let (x, y, z, pane) = (6.0, 4.0, 3.0, 3.0);
    let p = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
    let mut o = Obj::default();
    for (lo, hi) in [(0.0, pane), (pane, x)] {
        o.object("floor", "floor");
        o.quad(
            [
                p(lo, 0.0, 0.0),
                p(hi, 0.0, 0.0),
                p(hi, y, 0.0),
                p(lo, y, 0.0),
            ],
            1.0,
        );
        o.object("ceiling", "ceiling");
        o.quad(
            [p(lo, y, z), p(hi, y, z), p(hi, 0.0, z), p(lo, 0.0, z)],
            1.0,
        );
        o.object("walls", "wall");
        o.wall((hi, 0.0), (lo, 0.0), z);
        o.wall((lo, y), (hi, y), z);
    }
    o.wall((0.0, 0.0), (0.0, y), z);
    o.wall((x, y), (x, 0.0), z);
    o.object("pane", "glass");
    o.quad(
        [
            p(pane, 0.0, 0.0),
            p(pane, y, 0.0),
            p(pane, y, z),
            p(pane, 0.0, z),
        ],
        1.0,
    );
    o
}

/// The 6 × 4 × 3 m box room with a window 2.4 × 1.5 m (sill 0.9 m) in its south wall
/// (y = 0), glazed with one pane: the daylight example.
fn side_lit_room() -> Obj {
    let (x, y, z) = (6.0, 4.0, 3.0);
    let (w0, w1, sill, head) = (1.8, 4.2, 0.9, 2.4);
    let p = |x: f64, z: f64| DVec3::new(x, 0.0, z);
    let mut o = Obj::default();
    o.object("floor", "floor");
    o.level(x, y, 0.0, true);
    o.object("ceiling", "ceiling");
    o.level(x, y, z, false);
    o.object("walls", "wall");
    o.wall((0.0, 0.0), (0.0, y), z);
    o.wall((x, y), (x, 0.0), z);
    o.wall((0.0, y), (x, y), z);
    // The south wall round the window, facing in (+Y).
    for (a0, a1, b0, b1) in [
        (0.0, w0, 0.0, z),
        (w1, x, 0.0, z),
        (w0, w1, 0.0, sill),
        (w0, w1, head, z),
    ] {
        o.quad([p(a1, b0), p(a0, b0), p(a0, b1), p(a1, b1)], 1.0);
    }
    o.object("window", "glass");
    o.quad([p(w1, sill), p(w0, sill), p(w0, head), p(w1, head)], 1.0);
    o
}

/// The site of the planning example (`sunlight_site`): an existing terrace of three
/// storeys (30 × 10 × 9 m, its south face at y = 0) and, with `proposed`, a new
/// nine-storey block 12 m to its south (14 × 10 × 27 m).
fn sunlight_site(proposed: bool) -> Obj {
    let mut o = Obj::default();
    o.object("existing_terrace", "wall");
    o.cuboid(DVec3::new(0.0, 0.0, 0.0), DVec3::new(30.0, 10.0, 9.0));
    if proposed {
        o.object("new_block", "wall");
        o.cuboid(DVec3::new(9.0, -22.0, 0.0), DVec3::new(23.0, -12.0, 27.0));
    }
    o
}

/// The perforated panel: white, its holes from `map_d` (the rest of the materials are
/// [`ROOM_MTL`]'s).
const PERFORATED_MTL: &str = "newmtl perforated
Kd 0.7 0.7 0.7
map_d textures/perforation.png
";

/// A 4 × 4 × 3 m room with a 1.2 × 1.2 m perforated panel hung at 1.6 m (facing down,
/// one round hole per 0.15 m, half of it open) under the ceiling luminaire: the
/// alpha-mask example (its shadow on the floor is a grid of light spots).
fn perforated_panel() -> Obj {
    let p = |x: f64, y: f64| DVec3::new(x, y, 1.6);
    let mut o = Obj::default();
    o.room(
        DVec3::new(4.0, 4.0, 3.0),
        "floor",
        "wall",
        "wall",
        "ceiling",
    );
    o.object("panel", "perforated");
    o.quad([p(1.4, 2.6), p(2.6, 2.6), p(2.6, 1.4), p(1.4, 1.4)], 0.15);
    o
}

/// The perforation: a round hole (black in the grey mask) half the texel area, in each
/// 64 × 64 tile.
fn perforation() -> image::RgbaImage {
    // π r² = ½ · 64²
    let r2 = 0.5 * 64.0 * 64.0 / std::f64::consts::PI;
    image::RgbaImage::from_fn(64, 64, |x, y| {
        let (dx, dy) = (x as f64 + 0.5 - 32.0, y as f64 + 0.5 - 32.0);
        let v = if dx * dx + dy * dy < r2 { 0 } else { 255 };
        image::Rgba([v, v, v, 255])
    })
}

/// The furniture of the boxes room; the rest of its materials are [`ROOM_MTL`]'s.
const FURNITURE_MTL: &str = "newmtl furniture
Kd 0.4 0.4 0.4
";

const FURNISHED_MTL: &str = "newmtl floor_wood
Kd 0.55 0.55 0.55
Ks 0.04 0.04 0.04
Ns 60
map_Kd textures/wood.png
newmtl wall
Kd 0.6 0.58 0.55
newmtl plaster_bricks
Kd 0.62 0.5 0.42
map_Bump textures/bricks_normal.png
newmtl ceiling
Kd 0.75 0.75 0.75
newmtl oak
Kd 0.45 0.3 0.17
Ks 0.05 0.05 0.05
Ns 40
newmtl fabric
Kd 0.25 0.32 0.45
newmtl metal
Kd 0.15 0.15 0.15
Ks 0.5 0.5 0.5
Ns 120
newmtl canvas
Kd 0.7 0.45 0.2
newmtl canvas_dark
Kd 0.1 0.3 0.35
";

const STAGE_MTL: &str = "newmtl floor
Kd 0.3 0.3 0.32
Ks 0.1 0.1 0.1
Ns 80
newmtl wall
Kd 0.55 0.55 0.6
newmtl ceiling
Kd 0.4 0.4 0.4
newmtl mirror_ball
Kd 0.3 0.3 0.3
Ks 0.6 0.6 0.6
Ns 200
";

/// A wood-grain texture (sRGB).
fn wood() -> image::RgbaImage {
    image::RgbaImage::from_fn(256, 256, |x, y| {
        let plank = (y / 32) as f64;
        let grain = ((x as f64 * 0.09 + plank * 1.7).sin() * 0.5
            + (x as f64 * 0.023 + y as f64 * 0.05 + plank).sin() * 0.5)
            * 0.5
            + 0.5;
        let seam = if y % 32 == 0 { 0.6 } else { 1.0 };
        let v = (0.75 + 0.25 * grain) * seam;
        image::Rgba([(200.0 * v) as u8, (150.0 * v) as u8, (100.0 * v) as u8, 255])
    })
}

/// A tangent-space normal map of a brick wall (bricks 32 × 16 texels, mortar joints).
fn bricks_normal() -> image::RgbaImage {
    let height = |x: i64, y: i64| -> f64 {
        let (x, y) = (x.rem_euclid(256), y.rem_euclid(256));
        let row = y / 16;
        let xo = (x + if row % 2 == 1 { 16 } else { 0 }) % 32;
        let yo = y % 16;
        let edge = xo.min(31 - xo).min(yo.min(15 - yo)) as f64;
        (edge / 2.0).min(1.0)
    };
    image::RgbaImage::from_fn(256, 256, |x, y| {
        let (x, y) = (x as i64, y as i64);
        let dx = height(x + 1, y) - height(x - 1, y);
        let dy = height(x, y + 1) - height(x, y - 1);
        // Image rows go down while v goes up: flip the y slope.
        let n = DVec3::new(-dx * 1.5, dy * 1.5, 1.0).normalize();
        let enc = |c: f64| ((c * 0.5 + 0.5) * 255.0).round() as u8;
        image::Rgba([enc(n.x), enc(n.y), enc(n.z), 255])
    })
}

/// A disco-like effect light: 48 narrow beams (Gaussian, σ = 3°) spread over the sphere
/// on a Fibonacci lattice, 2.5° × 2.5° grid, Isym 0.
fn disco() -> Eulumdat {
    let dc = 2.5;
    let dg = 2.5;
    let c_angles: Vec<f64> = (0..144).map(|i| i as f64 * dc).collect();
    let gamma_angles: Vec<f64> = (0..73).map(|i| i as f64 * dg).collect();
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    let beams: Vec<DVec3> = (0..48)
        .map(|i| {
            let z = 1.0 - 2.0 * (i as f64 + 0.5) / 48.0;
            let r = (1.0 - z * z).sqrt();
            let a = golden * i as f64;
            DVec3::new(r * a.cos(), r * a.sin(), z)
        })
        .collect();
    let sigma = 3f64.to_radians();
    let intensities = c_angles
        .iter()
        .map(|&c| {
            gamma_angles
                .iter()
                .map(|&g| {
                    let d = goniolight::photometry::angles_to_direction(c, g);
                    let peak: f64 = beams
                        .iter()
                        .map(|b| {
                            let ang = d.dot(*b).clamp(-1.0, 1.0).acos();
                            (-0.5 * (ang / sigma).powi(2)).exp()
                        })
                        .sum();
                    (2.0 + 3000.0 * peak).round()
                })
                .collect()
        })
        .collect();
    Eulumdat {
        company: "goniolight (procedural)".into(),
        ityp: 1,
        symmetry: Symmetry::None,
        dc,
        dg,
        report_number: "effect".into(),
        luminaire_name: "Disco effect light, 48 beams".into(),
        luminaire_number: "GL-DISCO-48".into(),
        file_name: "disco.ldt".into(),
        date_user: "2026-11-22 goniolight examples/make_scenes.rs".into(),
        dimensions: Dimensions {
            length: 300.0,
            area_length: 300.0,
            ..Default::default()
        },
        dff_percent: 50.0,
        lorl_percent: 100.0,
        conversion_factor: 1.0,
        tilt_deg: 0.0,
        lamp_sets: vec![LampSet {
            count: 1,
            lamp_type: "LED".into(),
            flux_lm: 1000.0,
            color: "3000K".into(),
            cri: "1B".into(),
            watts: 12.0,
        }],
        direct_ratios: [0.5; 10],
        c_angles,
        gamma_angles,
        intensities,
    }
}

/// Materials of the Cornell box (reflectances after Goral et al. 1984; the light's
/// luminous exitance in lm/m²).
const CORNELL_MTL: &str =
    "# Cornell-box-like scene: diffuse reflectances, light exitance Ke in lm/m².
newmtl white
Kd 0.73 0.73 0.73
newmtl red
Kd 0.63 0.065 0.05
newmtl green
Kd 0.14 0.45 0.091
newmtl light
Kd 0.78 0.78 0.78
Ke 10000 10000 10000
";

/// A Cornell-box-like scene (5.56 × 5.59 × 5.49 m, open at the front, y = 0): white
/// floor, ceiling and back wall, red left and green right wall, an emitting panel under
/// the ceiling and two axis-aligned blocks.
fn cornell_box(o: &mut Obj) {
    let (x, y, z) = (5.56, 5.59, 5.49);
    let p = DVec3::new;
    o.object("floor", "white");
    o.quad(
        [p(0., 0., 0.), p(x, 0., 0.), p(x, y, 0.), p(0., y, 0.)],
        1.0,
    );
    o.object("ceiling", "white");
    o.quad([p(0., 0., z), p(0., y, z), p(x, y, z), p(x, 0., z)], 1.0);
    o.object("back", "white");
    o.quad([p(0., y, 0.), p(x, y, 0.), p(x, y, z), p(0., y, z)], 1.0);
    o.object("left", "red");
    o.quad(
        [p(0., 0., 0.), p(0., y, 0.), p(0., y, z), p(0., 0., z)],
        1.0,
    );
    o.object("right", "green");
    o.quad([p(x, 0., 0.), p(x, 0., z), p(x, y, z), p(x, y, 0.)], 1.0);
    o.object("light", "light");
    let (x0, x1, y0, y1, zl) = (2.13, 3.43, 2.27, 3.32, 5.48);
    o.quad(
        [p(x0, y0, zl), p(x0, y1, zl), p(x1, y1, zl), p(x1, y0, zl)],
        1.0,
    );
    o.object("short_block", "white");
    o.cuboid(p(3.0, 0.65, 0.0), p(4.65, 2.3, 1.65));
    o.object("tall_block", "white");
    o.cuboid(p(0.9, 2.9, 0.0), p(2.55, 4.55, 3.3));
}

fn main() -> anyhow::Result<()> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    // `make_scenes cad-office DIR`: only the large CAD-like office (not bundled: 17 MB).
    let args: Vec<String> = std::env::args().skip(1).collect();
    if let [what, dir] = args.as_slice() {
        anyhow::ensure!(what == "cad-office", "usage: make_scenes [cad-office DIR]");
        return cad_office(root, Path::new(dir), 350);
    }
    anyhow::ensure!(args.is_empty(), "usage: make_scenes [cad-office DIR]");
    let scenes = root.join("assets/scenes");
    std::fs::create_dir_all(scenes.join("textures"))?;
    let size = DVec3::new(6.0, 4.0, 3.0);

    let mut room = Obj::default();
    room.room(size, "floor", "wall", "wall", "ceiling");
    room.write_with_mtl(&scenes, "box_room", ROOM_MTL)?;

    let mut furnished = Obj::default();
    furnished.room(size, "floor_wood", "wall", "plaster_bricks", "ceiling");
    furniture(&mut furnished);
    furnished.write_with_mtl(&scenes, "furnished_room", FURNISHED_MTL)?;
    wood().save(scenes.join("textures/wood.png"))?;
    bricks_normal().save(scenes.join("textures/bricks_normal.png"))?;

    // The 52-triangle room and the same geometry as 2 600 CAD-like strips.
    boxes_room(size).write_with_mtl(
        &scenes,
        "boxes_room",
        &format!("{ROOM_MTL}{FURNITURE_MTL}"),
    )?;
    let scene = goniolight::scene::Scene::load(&scenes.join("boxes_room.toml"))?;
    write_fanned(&scene, 50, &scenes.join("cad_room.obj"), "boxes_room.mtl")?;

    // The box room with its back wall a mirror (the specular validation rooms).
    let mut mirror_room = Obj::default();
    mirror_room.room(size, "floor", "wall", "mirror", "ceiling");
    mirror_room.write_with_mtl(&scenes, "mirror_room", &format!("{ROOM_MTL}{MIRROR_MTL}"))?;
    glass_partition().write_with_mtl(
        &scenes,
        "glass_partition",
        &format!("{ROOM_MTL}{GLASS_MTL}"),
    )?;

    side_lit_room().write_with_mtl(&scenes, "side_lit_room", &format!("{ROOM_MTL}{GLASS_MTL}"))?;
    sunlight_site(true).write_with_mtl(&scenes, "sunlight_site", ROOM_MTL)?;
    sunlight_site(false).write_with_mtl(&scenes, "sunlight_site_existing", ROOM_MTL)?;

    let mut stage = Obj::default();
    stage.room(size, "floor", "wall", "wall", "ceiling");
    stage.object("mirror_ball", "mirror_ball");
    stage.cuboid(DVec3::new(2.9, 1.9, 2.15), DVec3::new(3.1, 2.1, 2.35));
    stage.object("rod", "mirror_ball");
    stage.cuboid(DVec3::new(2.99, 1.99, 2.35), DVec3::new(3.01, 2.01, 3.0));
    stage.write_with_mtl(&scenes, "effect_stage", STAGE_MTL)?;

    luminous_ceiling().write_with_mtl(
        &scenes,
        "luminous_ceiling",
        &format!("{ROOM_MTL}{LUMINOUS_CEILING_MTL}"),
    )?;

    perforated_panel().write_with_mtl(
        &scenes,
        "perforated_panel",
        &format!("{ROOM_MTL}{PERFORATED_MTL}"),
    )?;
    perforation().save(scenes.join("textures/perforation.png"))?;

    let mut cornell = Obj::default();
    cornell_box(&mut cornell);
    cornell.write_with_mtl(&scenes, "cornell_box", CORNELL_MTL)?;

    let ldt = disco();
    std::fs::write(
        root.join("luminaires/effects/disco.ldt"),
        ldt.to_ldt_string(),
    )?;
    println!("wrote assets/scenes/*.obj, *.mtl, textures/*.png and luminaires/effects/disco.ldt");
    Ok(())
}
