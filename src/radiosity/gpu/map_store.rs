//! Visibility maps kept for the shots that waiting receivers missed (perspective-driven
//! radiosity, [`super::deferred`]; opt-in: [`GpuSolver::set_map_store_bytes`]). When the
//! charts join, the catch-up copies the kept maps back into the batch's atlas instead of
//! drawing them again. They are the very maps the shot was received through, so the
//! charts that join get exactly the light they would have had.
//!
//! [`GpuSolver::set_map_store_bytes`]: super::GpuSolver::set_map_store_bytes

use crate::gpu::Gpu;
use crate::radiosity::atlas::{max_columns, tile_origin, VisibilityAtlas, MAP_FORMAT};

/// Bytes of maps kept by default: none. On an H200 the copies cost more than drawing
/// the maps again (eight furnished rooms, perspective-driven, to 5 % in view: 0.36–0.42 s
/// keeping them, 0.22–0.26 s drawing them; likely because every batch then moves the
/// whole atlas between render, copy and sampling layouts), on lavapipe they save a little (2.8× global against
/// 2.4–2.6× on two rooms), and the catch-up is exact (no texel at a depth edge flips).
pub const DEFAULT_MAP_STORE_BYTES: u64 = 0;
/// Bytes of the store's first texture (it doubles as it fills, within its budget and
/// the GPU's largest texture).
const FIRST_STORE_BYTES: u64 = 16 << 20;

/// Tiles of one side in one texture, handed out in order and freed all at once.
pub struct MapStore {
    texture: Option<wgpu::Texture>,
    /// Side of a tile, texels (the atlas's: set by the first tile kept).
    size: u32,
    /// Tiles per row, and rows now.
    columns: u32,
    rows: u32,
    /// The most tiles it may hold.
    most: u32,
    next: u32,
    budget: u64,
    /// Maps copied back for a catch-up so far (not drawn).
    pub reused: usize,
}

impl MapStore {
    /// A store of at most `budget` bytes (0: nothing is kept).
    pub fn new(budget: u64) -> MapStore {
        MapStore {
            texture: None,
            size: 0,
            columns: 1,
            rows: 0,
            most: 0,
            next: 0,
            budget,
            reused: 0,
        }
    }

    /// The first of `tiles` consecutive free tiles of side `size` (growing the store,
    /// its kept maps copied over in `enc`), or `None` when the budget is spent (or the
    /// side is not the one the store holds).
    pub fn allocate(
        &mut self,
        gpu: &Gpu,
        enc: &mut wgpu::CommandEncoder,
        size: u32,
        tiles: u32,
    ) -> Option<u32> {
        if self.size == 0 {
            let tile_bytes = (u64::from(size) * u64::from(size) * 4).max(1);
            self.size = size;
            self.columns = max_columns(gpu, size);
            let fit = u64::from(self.columns) * u64::from(self.columns);
            self.most = (self.budget / tile_bytes).min(fit) as u32;
        }
        if size != self.size || self.next + tiles > self.most {
            return None;
        }
        while self.next + tiles > self.columns * self.rows {
            self.grow(gpu, enc);
        }
        let first = self.next;
        self.next += tiles;
        Some(first)
    }

    /// Whether it may keep anything (a budget above zero).
    pub fn is_enabled(&self) -> bool {
        self.budget > 0
    }

    /// Frees every tile (nothing kept is needed any more).
    pub fn clear(&mut self) {
        self.next = 0;
    }

    /// Records copies of a cell's `tiles` maps between the atlas (its tiles from
    /// `atlas_tile`) and the store (from `slot`): into the store with `keep`, else back
    /// into the atlas (counted in [`MapStore::reused`]).
    pub fn copy_cell(
        &mut self,
        enc: &mut wgpu::CommandEncoder,
        atlas: &VisibilityAtlas,
        (atlas_tile, slot, tiles): (u32, u32, u32),
        keep: bool,
    ) {
        let Some(texture) = &self.texture else {
            return;
        };
        for f in 0..tiles {
            let in_atlas = (&atlas.texture, atlas.origin(atlas_tile + f));
            let in_store = (texture, self.origin(slot + f));
            if keep {
                copy(enc, in_atlas, in_store, self.size);
            } else {
                copy(enc, in_store, in_atlas, self.size);
            }
        }
        if !keep {
            self.reused += tiles as usize;
        }
    }

    fn origin(&self, tile: u32) -> (u32, u32) {
        tile_origin(tile, self.columns, self.size)
    }

    /// Twice the rows (at first, [`FIRST_STORE_BYTES`] of them), the kept maps copied.
    fn grow(&mut self, gpu: &Gpu, enc: &mut wgpu::CommandEncoder) {
        let row_bytes = u64::from(self.columns) * u64::from(self.size).pow(2) * 4;
        let first = (FIRST_STORE_BYTES / row_bytes.max(1)).max(1) as u32;
        let max_rows = self.most.div_ceil(self.columns);
        let rows = (self.rows * 2).max(first).min(max_rows);
        let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("kept visibility maps"),
            size: wgpu::Extent3d {
                width: self.columns * self.size,
                height: rows * self.size,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: MAP_FORMAT,
            // Renderable only so that wgpu zeroes a new store by a render pass's clear
            // rather than by copies from a zero buffer.
            usage: wgpu::TextureUsages::COPY_SRC
                | wgpu::TextureUsages::COPY_DST
                | wgpu::TextureUsages::RENDER_ATTACHMENT,
            view_formats: &[],
        });
        if let Some(old) = &self.texture {
            if self.next > 0 {
                enc.copy_texture_to_texture(
                    old.as_image_copy(),
                    texture.as_image_copy(),
                    wgpu::Extent3d {
                        width: self.columns * self.size,
                        height: self.rows * self.size,
                        depth_or_array_layers: 1,
                    },
                );
            }
        }
        self.texture = Some(texture);
        self.rows = rows;
    }
}

/// Records a copy of the `size` × `size` square at `from` to `to`.
fn copy(
    enc: &mut wgpu::CommandEncoder,
    from: (&wgpu::Texture, (u32, u32)),
    to: (&wgpu::Texture, (u32, u32)),
    size: u32,
) {
    fn at<'t>(
        (texture, (x, y)): (&'t wgpu::Texture, (u32, u32)),
    ) -> wgpu::TexelCopyTextureInfo<'t> {
        wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: 0,
            origin: wgpu::Origin3d { x, y, z: 0 },
            aspect: wgpu::TextureAspect::All,
        }
    }
    enc.copy_texture_to_texture(
        at(from),
        at(to),
        wgpu::Extent3d {
            width: size,
            height: size,
            depth_or_array_layers: 1,
        },
    );
}
