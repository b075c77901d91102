//! The visibility maps of a batch of shooting cells, side by side in one texture: every
//! face of every cell is a square tile, drawn with its own viewport in one render pass,
//! and the receive pass reads each cell's tiles from the same texture. One pass per
//! batch instead of one per face lets the GPU overlap the faces' draws (a pass per face,
//! each followed by its receive dispatch, left an H200 mostly idle between them). Each
//! tile is cleared by a draw of its own, so a small batch in a large atlas costs no more
//! than in a small one; the atlas is bounded by [`MAX_ATLAS_BYTES`] (an unbounded one,
//! grown to a first shot's thousands of cells, made every later batch clear gigabytes).

use crate::gpu::Gpu;

/// Format of the maps: the distance to the nearest surface, m.
pub const MAP_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Float;
/// Format of the maps' depth.
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// Most bytes of the maps' texture (as many again for their depth).
pub const MAX_ATLAS_BYTES: u64 = 64 << 20;

/// Square tiles of `size` texels in rows of `columns`; grown as batches grow.
pub struct VisibilityAtlas {
    /// Side of a tile (a hemicube face or a stereographic map), texels.
    pub size: u32,
    /// Tiles per row.
    pub columns: u32,
    /// Rows.
    pub rows: u32,
    /// The maps' texture.
    pub texture: wgpu::Texture,
    /// The maps (sampled by the receive pass).
    pub view: wgpu::TextureView,
    /// Their depth.
    pub depth_view: wgpu::TextureView,
}

impl VisibilityAtlas {
    /// An atlas of tiles of `size` holding at least `tiles` (within the GPU's limits).
    pub fn new(gpu: &Gpu, size: u32, tiles: u32) -> VisibilityAtlas {
        let (columns, rows) = layout(tiles, max_columns(gpu, size));
        let texture = |label: &str, format, usage| {
            gpu.device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width: columns * size,
                    height: rows * size,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT | usage,
                view_formats: &[],
            })
        };
        // The maps are sampled by the receive pass, copied to and from the kept maps
        // (radiosity/gpu/map_store.rs) and written by the compute rasterizer
        // (radiosity/gpu/raster.rs).
        let maps = texture(
            "visibility maps",
            MAP_FORMAT,
            wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC
                | wgpu::TextureUsages::COPY_DST
                | wgpu::TextureUsages::STORAGE_BINDING,
        );
        let depth = texture(
            "visibility depth",
            DEPTH_FORMAT,
            wgpu::TextureUsages::empty(),
        );
        VisibilityAtlas {
            size,
            columns,
            rows,
            view: maps.create_view(&Default::default()),
            depth_view: depth.create_view(&Default::default()),
            texture: maps,
        }
    }

    /// Tiles it holds.
    pub fn capacity(&self) -> u32 {
        self.columns * self.rows
    }

    /// The most tiles an atlas of this tile size holds on `gpu`: within
    /// [`MAX_ATLAS_BYTES`] and the largest texture, but always one hemicube's five.
    pub fn max_tiles(gpu: &Gpu, size: u32) -> u32 {
        let side = max_columns(gpu, size);
        let by_bytes = MAX_ATLAS_BYTES / (u64::from(size) * u64::from(size) * 4).max(1);
        (by_bytes.min(u64::from(side * side)) as u32).max(5.min(side * side))
    }

    /// Makes room for `tiles` (a new, larger texture when needed; the old maps are lost).
    pub fn reserve(&mut self, gpu: &Gpu, tiles: u32) {
        if tiles > self.capacity() {
            *self = VisibilityAtlas::new(gpu, self.size, tiles);
        }
    }

    /// Texel of the top-left corner of tile `tile`.
    pub fn origin(&self, tile: u32) -> (u32, u32) {
        tile_origin(tile, self.columns, self.size)
    }
}

/// Most tiles of `size` per row (and rows) the GPU's largest 2D texture holds.
pub(crate) fn max_columns(gpu: &Gpu, size: u32) -> u32 {
    (gpu.device.limits().max_texture_dimension_2d / size.max(1)).max(1)
}

/// Columns and rows for `tiles` tiles in rows of at most `max_columns`: as square as the
/// rows allow, never more rows than columns allow either.
fn layout(tiles: u32, max_columns: u32) -> (u32, u32) {
    let tiles = tiles.max(1);
    let columns = ((tiles as f64).sqrt().ceil() as u32).clamp(1, max_columns);
    let rows = tiles.div_ceil(columns).min(max_columns);
    (columns, rows)
}

/// Texel of the top-left corner of tile `tile` in rows of `columns` tiles of `size`
/// (`map_reaches` in radiosity.wgsl does the same).
pub(crate) fn tile_origin(tile: u32, columns: u32, size: u32) -> (u32, u32) {
    ((tile % columns) * size, (tile / columns) * size)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layouts_hold_the_tiles_asked_for_within_the_limit() {
        for max_columns in [1, 2, 8, 32] {
            for tiles in 1..400 {
                let (c, r) = layout(tiles, max_columns);
                assert!(
                    c <= max_columns && r <= max_columns,
                    "{tiles} {max_columns}"
                );
                assert!(
                    c * r >= tiles.min(max_columns * max_columns),
                    "{tiles} tiles in {c}×{r} (limit {max_columns})"
                );
                // Not needlessly large: one row fewer would not hold them.
                assert!(c * (r - 1) < tiles, "{tiles}: {c}×{r}");
            }
        }
    }

    #[test]
    fn tiles_do_not_overlap() {
        let (columns, size) = (7, 16);
        let mut seen = std::collections::HashSet::new();
        for tile in 0..49 {
            let (x, y) = tile_origin(tile, columns, size);
            assert_eq!((x % size, y % size), (0, 0));
            assert!(x < columns * size);
            assert!(seen.insert((x, y)));
        }
    }
}
