//! Bind group layouts shared by the renderer's pipelines: group 0 = frame (camera, lights,
//! light distributions), group 1 = material.

use crate::gpu::Gpu;

/// The layouts and the material sampler.
pub struct Layouts {
    /// Group 0: `Frame` uniform, lights, LDT atlas, LDT info; shadow info, shadow mask,
    /// paraboloid maps and their comparison sampler; the radiosity light map and its
    /// sampler.
    pub frame: wgpu::BindGroupLayout,
    /// Group 1: material uniform, diffuse map, normal map, sampler.
    pub material: wgpu::BindGroupLayout,
    /// Linear, repeating.
    pub material_sampler: wgpu::Sampler,
    /// Linear, clamped: the radiosity light map.
    pub light_map_sampler: wgpu::Sampler,
}

/// A bind group layout entry.
pub(crate) fn entry(
    binding: u32,
    visibility: wgpu::ShaderStages,
    ty: wgpu::BindingType,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty,
        count: None,
    }
}

fn buffer(ty: wgpu::BufferBindingType) -> wgpu::BindingType {
    buffer_binding(ty, false)
}

/// A buffer binding, with or without a dynamic offset.
pub(crate) fn buffer_binding(ty: wgpu::BufferBindingType, dynamic: bool) -> wgpu::BindingType {
    wgpu::BindingType::Buffer {
        ty,
        has_dynamic_offset: dynamic,
        min_binding_size: None,
    }
}

/// A sampled texture binding.
fn texture(
    sample_type: wgpu::TextureSampleType,
    dim: wgpu::TextureViewDimension,
) -> wgpu::BindingType {
    wgpu::BindingType::Texture {
        sample_type,
        view_dimension: dim,
        multisampled: false,
    }
}

impl Layouts {
    /// Creates the layouts.
    pub fn new(gpu: &Gpu) -> Layouts {
        use wgpu::ShaderStages as S;
        let storage = buffer(wgpu::BufferBindingType::Storage { read_only: true });
        let filterable = texture(
            wgpu::TextureSampleType::Float { filterable: true },
            wgpu::TextureViewDimension::D2,
        );
        let frame = gpu
            .device
            .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("frame"),
                entries: &[
                    entry(
                        0,
                        S::VERTEX_FRAGMENT,
                        buffer(wgpu::BufferBindingType::Uniform),
                    ),
                    entry(1, S::FRAGMENT, storage),
                    entry(
                        2,
                        S::FRAGMENT,
                        texture(
                            wgpu::TextureSampleType::Float { filterable: false },
                            wgpu::TextureViewDimension::D2Array,
                        ),
                    ),
                    entry(3, S::FRAGMENT, storage),
                    entry(6, S::FRAGMENT, storage),
                    entry(
                        7,
                        S::FRAGMENT,
                        texture(
                            wgpu::TextureSampleType::Float { filterable: true },
                            wgpu::TextureViewDimension::D2Array,
                        ),
                    ),
                    entry(
                        14,
                        S::FRAGMENT,
                        wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                    ),
                    entry(
                        15,
                        S::FRAGMENT,
                        texture(
                            wgpu::TextureSampleType::Float { filterable: true },
                            wgpu::TextureViewDimension::CubeArray,
                        ),
                    ),
                    entry(8, S::FRAGMENT, buffer(wgpu::BufferBindingType::Uniform)),
                    entry(
                        9,
                        S::FRAGMENT,
                        texture(
                            wgpu::TextureSampleType::Uint,
                            wgpu::TextureViewDimension::D2Array,
                        ),
                    ),
                    entry(
                        10,
                        S::FRAGMENT,
                        texture(
                            wgpu::TextureSampleType::Depth,
                            wgpu::TextureViewDimension::D2Array,
                        ),
                    ),
                    entry(
                        11,
                        S::FRAGMENT,
                        wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Comparison),
                    ),
                    entry(12, S::FRAGMENT, filterable),
                    entry(
                        13,
                        S::FRAGMENT,
                        wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                    ),
                ],
            });
        let material = gpu
            .device
            .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("material"),
                entries: &[
                    entry(0, S::FRAGMENT, buffer(wgpu::BufferBindingType::Uniform)),
                    entry(1, S::FRAGMENT, filterable),
                    entry(2, S::FRAGMENT, filterable),
                    entry(
                        3,
                        S::FRAGMENT,
                        wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                    ),
                ],
            });
        let material_sampler = gpu.device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("material"),
            address_mode_u: wgpu::AddressMode::Repeat,
            address_mode_v: wgpu::AddressMode::Repeat,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            // Trilinear over the mip chain, anisotropic at grazing angles (floors, walls
            // seen along their length).
            mipmap_filter: wgpu::MipmapFilterMode::Linear,
            anisotropy_clamp: 16,
            ..Default::default()
        });
        let light_map_sampler = gpu.device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("light map"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        Layouts {
            frame,
            material,
            material_sampler,
            light_map_sampler,
        }
    }
}
