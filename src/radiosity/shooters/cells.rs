//! A shooter's cells: a chart's patches, or a planar piece's elements binned into the
//! square cells of a grid in its plane (with coarser levels for the links), each cell a
//! shooting patch with its polygon, centre and frame.

use glam::{DVec2, DVec3};

use super::super::clusters::obb::convex_hull;
use super::super::clusters::Obb;
use super::super::polygon::{area_centroid, clip_square, outline};
use super::super::scene::RadiosityScene;
use super::{PlannedPatch, ShotPlan};

/// The plane a piece's cells lie in and the pieces they shoot.
pub(super) struct PieceFrame {
    /// Unit normal.
    pub(super) normal: DVec3,
    /// The pieces (first, end).
    pub(super) pieces: [u32; 2],
}

/// A chart shoots from its patches (their elements are contiguous).
pub(super) fn chart_plan(scene: &RadiosityScene, c: usize, pieces: [u32; 2]) -> ShotPlan {
    let el = &scene.elements;
    let chart = &el.charts[c];
    let patches = el.patches[chart.first_patch as usize..][..chart.patch_count as usize]
        .iter()
        .map(|p| PlannedPatch {
            first: p.first - chart.first,
            count: p.count,
            polygon: p.polygon.clone(),
            centroid: p.centroid,
            normal: chart.normal,
            area: p.area,
            element_area: p.area,
            level: 0,
            parent: u32::MAX,
            radius: radius(p.centroid, &p.polygon, &[]),
            pieces,
            merged: false,
        })
        .collect();
    ShotPlan {
        order: (chart.first..chart.first + chart.count).collect(),
        patches,
        shot: chart.count,
    }
}

/// A piece's elements binned by centroid into square cells of the grid's side laid from
/// its box's corner, plus up to `levels` coarser levels (sides doubling; the top level has
/// at least one cell over the whole piece or is `levels` up). Each non-empty cell is a
/// patch whose polygon is the convex hull of the piece's triangles clipped to the cell
/// (the exact surface inside the cell wherever that is convex), in the plane through its
/// elements. A level's cells' polygons tile the surface; an element straddling two cells
/// shoots from the one holding its centroid, so a cell shoots its elements' mean
/// radiosity (power over their area) from its polygon. Elements are ordered along the
/// Z-order curve of their finest cells, so every cell's elements are one range.
pub(super) fn cluster_plan(
    scene: &RadiosityScene,
    elements: &[u32],
    grid: &Grid,
    at: &PieceFrame,
    levels: u32,
) -> ShotPlan {
    let el = &scene.elements;
    let top = levels.min(grid.levels_to_one_cell());
    let mut keyed: Vec<(u64, u32, (u64, u64))> = elements
        .iter()
        .map(|&e| {
            let ij = grid.column_row(grid.plane(el.position[e as usize]));
            (z_order(ij), e, ij)
        })
        .collect();
    keyed.sort_unstable();
    let order: Vec<u32> = keyed.iter().map(|k| k.1).collect();
    let grids: Vec<Grid> = (0..=top).map(|k| grid.coarser(k)).collect();
    let triangles = triangles_of(scene, &order);
    let pieces: Vec<_> = grids
        .iter()
        .map(|g| g.triangle_pieces(scene, &triangles))
        .collect();
    let mut plan = ShotPlan {
        shot: order.len() as u32,
        order,
        patches: Vec::new(),
    };
    // Depth first: a cell, then its children (the next level's groups in its range).
    let mut stack: Vec<(u32, usize, usize, u32)> = groups(&keyed, 0, keyed.len(), top)
        .into_iter()
        .rev()
        .map(|(a, b)| (top, a, b, u32::MAX))
        .collect();
    while let Some((level, start, end, parent)) = stack.pop() {
        let (i, j) = keyed[start].2;
        let g = &grids[level as usize];
        let cell = (j >> level).min(g.rows - 1) * g.cols + (i >> level).min(g.cols - 1);
        let members = &plan.order[start..end];
        let outline = g.outline(
            cell,
            pieces[level as usize]
                .get(&cell)
                .map_or(&[][..], Vec::as_slice),
        );
        let here = plan.patches.len() as u32;
        let mut patch = cell_patch(
            scene,
            members,
            &outline,
            (g.u, g.v),
            at,
            start,
            level,
            parent,
        );
        if level > 0 {
            // A coarse cell of a piece that is not convex may have its centre off the
            // surface (inside a column standing on the floor): it looks from its element
            // nearest to that centre.
            patch.centroid = nearest_member(scene, members, patch.centroid);
        }
        plan.patches.push(patch);
        if level > 0 {
            for (a, b) in groups(&keyed, start, end, level - 1).into_iter().rev() {
                stack.push((level - 1, a, b, here));
            }
        }
    }
    plan
}

/// Per cell of a grid, the corners of the triangle pieces inside it.
type CellPieces = rustc_hash::FxHashMap<u64, Vec<DVec2>>;

/// The triangles of the charts holding `elements` (each once).
fn triangles_of(scene: &RadiosityScene, elements: &[u32]) -> Vec<u32> {
    let el = &scene.elements;
    let mut charts: Vec<u32> = elements.iter().map(|&e| el.chart[e as usize]).collect();
    charts.sort_unstable();
    charts.dedup();
    charts
        .iter()
        .flat_map(|&c| el.charts[c as usize].triangles.iter().copied())
        .collect()
}

/// The ranges of `keyed[start..end]` that share a cell at `level` (Z-order keys agree
/// above their lowest 2 · level bits).
fn groups(
    keyed: &[(u64, u32, (u64, u64))],
    start: usize,
    end: usize,
    level: u32,
) -> Vec<(usize, usize)> {
    let shift = 2 * level;
    let mut out = Vec::new();
    let mut a = start;
    while a < end {
        let key = keyed[a].0 >> shift;
        let b = a + keyed[a..end].partition_point(|k| k.0 >> shift == key);
        out.push((a, b));
        a = b;
    }
    out
}

/// Of `members`' elements, the position nearest `centre`.
pub(super) fn nearest_member(scene: &RadiosityScene, members: &[u32], centre: DVec3) -> DVec3 {
    let el = &scene.elements;
    members
        .iter()
        .map(|&e| el.position[e as usize])
        .min_by(|a, b| {
            a.distance_squared(centre)
                .total_cmp(&b.distance_squared(centre))
        })
        .unwrap_or(centre)
}

/// The patch of one cell: its `members` (from `order[start..]`) and its outline in the
/// plane coordinates along `(u, v)`, in the plane through their centre facing `at.normal`
/// (its radius measured from their area-weighted centre).
#[allow(clippy::too_many_arguments)]
pub(super) fn cell_patch(
    scene: &RadiosityScene,
    members: &[u32],
    outline: &[DVec2],
    (u, v): (DVec3, DVec3),
    at: &PieceFrame,
    start: usize,
    level: u32,
    parent: u32,
) -> PlannedPatch {
    let el = &scene.elements;
    let normal = at.normal;
    let element_area: f64 = members.iter().map(|&e| el.area[e as usize]).sum();
    let centroid = members
        .iter()
        .map(|&e| el.position[e as usize] * el.area[e as usize])
        .sum::<DVec3>()
        / element_area.max(1e-300);
    let offset = normal * centroid.dot(normal);
    let mut polygon: Vec<DVec3> = outline.iter().map(|q| u * q.x + v * q.y + offset).collect();
    if (polygon[1] - polygon[0])
        .cross(polygon[2] - polygon[0])
        .dot(normal)
        < 0.0
    {
        polygon.reverse();
    }
    let positions: Vec<DVec3> = members.iter().map(|&e| el.position[e as usize]).collect();
    PlannedPatch {
        first: start as u32,
        count: members.len() as u32,
        radius: radius(centroid, &polygon, &positions),
        polygon,
        centroid,
        normal,
        area: area_centroid(outline).0.abs(),
        element_area,
        level,
        parent,
        pieces: at.pieces,
        merged: false,
    }
}

/// The largest distance from `centre` to any of `polygon` and `points`.
fn radius(centre: DVec3, polygon: &[DVec3], points: &[DVec3]) -> f64 {
    polygon
        .iter()
        .chain(points)
        .map(|p| p.distance(centre))
        .fold(0.0, f64::max)
}

/// The Z-order (Morton) key of a cell: the bits of column and row interleaved, so the
/// cells of any coarser aligned cell are one range of keys.
pub(super) fn z_order((i, j): (u64, u64)) -> u64 {
    fn spread(x: u64) -> u64 {
        let mut x = x & 0xffff_ffff;
        x = (x | (x << 16)) & 0x0000_ffff_0000_ffff;
        x = (x | (x << 8)) & 0x00ff_00ff_00ff_00ff;
        x = (x | (x << 4)) & 0x0f0f_0f0f_0f0f_0f0f;
        x = (x | (x << 2)) & 0x3333_3333_3333_3333;
        (x | (x << 1)) & 0x5555_5555_5555_5555
    }
    spread(i) | (spread(j) << 1)
}

/// A square grid in a cluster's plane: plane coordinates along `u` and `v`, cells of
/// `side` metres from `lo`, clipped to `hi`.
pub(super) struct Grid {
    lo: DVec2,
    hi: DVec2,
    side: f64,
    cols: u64,
    rows: u64,
    u: DVec3,
    v: DVec3,
}

impl Grid {
    /// Cells of `side` metres over the plane of `obb` (axes 0 and 1).
    pub(super) fn new(obb: &Obb, side: f64) -> Grid {
        let [u, v, _] = obb.axes;
        let lo = DVec2::new(
            obb.centre.dot(u) - obb.half.x,
            obb.centre.dot(v) - obb.half.y,
        );
        let hi = lo + 2.0 * DVec2::new(obb.half.x, obb.half.y);
        Grid::with_side(lo, hi, side, u, v)
    }

    fn with_side(lo: DVec2, hi: DVec2, side: f64, u: DVec3, v: DVec3) -> Grid {
        Grid {
            lo,
            hi,
            side,
            cols: (((hi.x - lo.x) / side).ceil() as u64).max(1),
            rows: (((hi.y - lo.y) / side).ceil() as u64).max(1),
            u,
            v,
        }
    }

    /// The grid `level` levels up: cells 2^level times the side, from the same corner, so
    /// cell (i, j) holds the fine cells (i ≫ level, j ≫ level) maps to it.
    fn coarser(&self, level: u32) -> Grid {
        let side = self.side * f64::from(1u32 << level);
        Grid::with_side(self.lo, self.hi, side, self.u, self.v)
    }

    /// How many levels up one cell covers the grid.
    pub(super) fn levels_to_one_cell(&self) -> u32 {
        let mut level = 0;
        while (self.cols.max(self.rows) - 1) >> level > 0 {
            level += 1;
        }
        level
    }

    pub(super) fn plane(&self, p: DVec3) -> DVec2 {
        DVec2::new(p.dot(self.u), p.dot(self.v))
    }

    /// Column and row of the cell holding `q` (clamped to the grid).
    pub(super) fn column_row(&self, q: DVec2) -> (u64, u64) {
        let q = (q - self.lo) / self.side;
        let i = (q.x.max(0.0) as u64).min(self.cols - 1);
        let j = (q.y.max(0.0) as u64).min(self.rows - 1);
        (i, j)
    }

    fn bounds(&self, cell: u64) -> (DVec2, DVec2) {
        let (i, j) = (cell % self.cols, cell / self.cols);
        let lo = self.lo + DVec2::new(i as f64, j as f64) * self.side;
        (lo, (lo + DVec2::splat(self.side)).min(self.hi))
    }

    /// Per cell, the corners of the pieces of `triangles` inside it.
    fn triangle_pieces(&self, scene: &RadiosityScene, triangles: &[u32]) -> CellPieces {
        let mesh = &scene.casters;
        let mut pieces = CellPieces::default();
        for &t in triangles {
            let mut c = mesh.triangles[t as usize].map(|i| self.plane(mesh.positions[i as usize]));
            if (c[1] - c[0]).perp_dot(c[2] - c[0]) < 0.0 {
                c.swap(1, 2);
            }
            let (i0, j0) = self.column_row(c[0].min(c[1]).min(c[2]));
            let (i1, j1) = self.column_row(c[0].max(c[1]).max(c[2]));
            for j in j0..=j1 {
                for i in i0..=i1 {
                    let cell = j * self.cols + i;
                    let (lo, hi) = self.bounds(cell);
                    let piece = clip_square(lo, hi, &c);
                    if piece.len() >= 3 {
                        pieces.entry(cell).or_default().extend(piece);
                    }
                }
            }
        }
        pieces
    }

    /// The convex hull of a cell's triangle pieces: at most 8 corners (the shot record's
    /// limit; more become the hull's bounding rectangle), at least a triangle (the cell
    /// when the pieces have no area).
    fn outline(&self, cell: u64, pieces: &[DVec2]) -> Vec<DVec2> {
        let (lo, hi) = self.bounds(cell);
        outline(&convex_hull(pieces), lo, hi)
    }
}
