//! The GPU context: instance, adapter, device and queue, built headless (for the CLI and
//! tests) with the adapter chosen by `WGPU_BACKEND` / `WGPU_ADAPTER_NAME`; WGSL sources
//! compiled in; read-back helpers.

pub mod shaders;

/// Why no GPU context could be made.
#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    /// No adapter at all (or none matching `WGPU_ADAPTER_NAME`).
    #[error("no GPU adapter found{0}. On Debian/Ubuntu without a GPU driver, install the software Vulkan driver: `apt-get install mesa-vulkan-drivers libvulkan1` (lavapipe). `WGPU_BACKEND` (vulkan, gl, …) and `WGPU_ADAPTER_NAME` (a part of the adapter's name) choose among several.")]
    NoAdapter(String),
    /// The adapter refused to create a device.
    #[error("the GPU adapter {adapter:?} could not create a device: {source}")]
    Device {
        /// The adapter's name.
        adapter: String,
        /// What wgpu said.
        source: wgpu::RequestDeviceError,
    },
    /// The adapter's backend lacks what goniolight's GPU code needs (wgpu's GL backend:
    /// no float render targets, downlevel compute): refused before any work, so no
    /// command can print a number it did not compute.
    #[error("{0}")]
    Unsupported(String),
    /// A GPU operation failed (validation, mapping, timeout).
    #[error("GPU: {0}")]
    Operation(String),
    /// The work asks more than the device allows (buffer size, texture layers): refused
    /// before anything is uploaded.
    #[error("{0}")]
    Limit(String),
}

/// A colour attachment cleared to `colour` and stored: how every colour pass of the
/// renderer, the radiosity solver and the viewer starts.
pub fn cleared_attachment(
    view: &wgpu::TextureView,
    colour: wgpu::Color,
) -> wgpu::RenderPassColorAttachment<'_> {
    wgpu::RenderPassColorAttachment {
        view,
        depth_slice: None,
        resolve_target: None,
        ops: wgpu::Operations {
            load: wgpu::LoadOp::Clear(colour),
            store: wgpu::StoreOp::Store,
        },
    }
}

/// Refuses an adapter whose backend goniolight's GPU code does not run correctly on:
/// wgpu's OpenGL backend (picked when no Vulkan driver is installed) renders nothing into
/// the 32-bit float targets the renderer and the illuminance queries use, so its numbers
/// would be zeros; any adapter without float render targets or compute shaders likewise.
pub fn check_backend(adapter: &wgpu::Adapter) -> Result<(), GpuError> {
    let info = adapter.get_info();
    let float_target = adapter
        .get_texture_format_features(wgpu::TextureFormat::Rgba32Float)
        .allowed_usages
        .contains(wgpu::TextureUsages::RENDER_ATTACHMENT);
    let compute = adapter
        .get_downlevel_capabilities()
        .flags
        .contains(wgpu::DownlevelFlags::COMPUTE_SHADERS);
    let missing = match () {
        _ if info.backend == wgpu::Backend::Gl => "the OpenGL backend is not supported",
        _ if !float_target => "it cannot render into 32-bit float (Rgba32Float) targets",
        _ if !compute => "it has no compute shaders",
        _ => return Ok(()),
    };
    Err(GpuError::Unsupported(format!(
        "GPU adapter {:?} ({:?} backend) refused: {missing}, so goniolight's images and lux \
         values would be wrong. Use a Vulkan, Metal or DirectX 12 driver: on Debian/Ubuntu \
         without a GPU driver, install the software Vulkan driver (`apt-get install \
         mesa-vulkan-drivers libvulkan1`); if one is installed, unset WGPU_BACKEND or set \
         WGPU_BACKEND=vulkan.",
        info.name, info.backend
    )))
}

/// A `D2` view of layer `layer` of an array texture (a render target per layer).
pub fn layer_view(texture: &wgpu::Texture, layer: u32) -> wgpu::TextureView {
    texture.create_view(&wgpu::TextureViewDescriptor {
        dimension: Some(wgpu::TextureViewDimension::D2),
        base_array_layer: layer,
        array_layer_count: Some(1),
        ..Default::default()
    })
}

/// A headless GPU context (cheap to clone: wgpu's handles are shared).
#[derive(Clone)]
pub struct Gpu {
    /// The instance.
    pub instance: wgpu::Instance,
    /// The chosen adapter.
    pub adapter: wgpu::Adapter,
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// Objects built once per device and shared by whoever asks again ([`Gpu::cached`]).
    cache: std::sync::Arc<std::sync::Mutex<DeviceCache>>,
}

/// [`Gpu::cached`]'s objects, one per type.
type DeviceCache =
    std::collections::HashMap<std::any::TypeId, std::sync::Arc<dyn std::any::Any + Send + Sync>>;

impl Gpu {
    /// Creates a headless context. `WGPU_BACKEND` limits the backends, `WGPU_ADAPTER_NAME`
    /// picks the first adapter whose name contains it (case-insensitive).
    pub fn headless() -> Result<Gpu, GpuError> {
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        Gpu::with_instance(instance, None)
    }

    /// The process's headless context, created on first use and shared by every later
    /// call (a batch of commands starts the GPU once). A failed start is not kept.
    pub fn shared() -> Result<Gpu, GpuError> {
        static SHARED: std::sync::Mutex<Option<Gpu>> = std::sync::Mutex::new(None);
        let mut shared = SHARED.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(gpu) = shared.as_ref() {
            return Ok(gpu.clone());
        }
        let gpu = Gpu::headless()?;
        *shared = Some(gpu.clone());
        Ok(gpu)
    }

    /// Creates a context on `instance` whose adapter can present to `surface` (the
    /// viewer's window) when one is given; the adapter is chosen as for [`Gpu::headless`].
    pub fn with_instance(
        instance: wgpu::Instance,
        surface: Option<&wgpu::Surface<'_>>,
    ) -> Result<Gpu, GpuError> {
        let wanted = std::env::var("WGPU_ADAPTER_NAME")
            .ok()
            .map(|s| s.to_lowercase());
        let adapter = match &wanted {
            Some(name) => {
                let all = pollster::block_on(instance.enumerate_adapters(wgpu::Backends::all()));
                let names: Vec<String> = all.iter().map(|a| a.get_info().name).collect();
                all.into_iter()
                    .find(|a| a.get_info().name.to_lowercase().contains(name.as_str()))
                    .ok_or_else(|| {
                        GpuError::NoAdapter(format!(
                            " matching WGPU_ADAPTER_NAME={name:?} (adapters: {names:?})"
                        ))
                    })?
            }
            None => pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
                power_preference: wgpu::PowerPreference::HighPerformance,
                compatible_surface: surface,
                ..Default::default()
            }))
            .map_err(|e| GpuError::NoAdapter(format!(" ({e})")))?,
        };
        let info = adapter.get_info();
        check_backend(&adapter)?;
        let wanted_features = wgpu::Features::DEPTH32FLOAT_STENCIL8
                | wgpu::Features::DEPTH_CLIP_CONTROL
                // The radiosity benchmark's GPU pass timers (radiosity/gpu/timers.rs).
                | wgpu::Features::TIMESTAMP_QUERY;
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("goniolight"),
            required_features: adapter.features() & wanted_features,
            required_limits: required_limits(&adapter.limits()),
            ..Default::default()
        }))
        .map_err(|source| GpuError::Device {
            adapter: info.name.clone(),
            source,
        })?;
        Ok(Gpu {
            instance,
            adapter,
            device,
            queue,
            cache: Default::default(),
        })
    }

    /// The one `T` of this device, made by `make` the first time it is asked for: pipelines
    /// that every solver of a process would otherwise compile again (about 20 ms each time
    /// for the radiosity solver's).
    pub fn cached<T: std::any::Any + Send + Sync>(
        &self,
        make: impl FnOnce() -> T,
    ) -> std::sync::Arc<T> {
        let key = std::any::TypeId::of::<T>();
        let mut cache = self.cache.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(found) = cache.get(&key).and_then(|v| v.clone().downcast::<T>().ok()) {
            return found;
        }
        let made = std::sync::Arc::new(make());
        cache.insert(key, made.clone());
        made
    }

    /// The depth-stencil format of the renderer's targets: 32-bit float depth with an
    /// 8-bit stencil where the adapter has it, 24-bit depth otherwise.
    pub fn depth_stencil_format(&self) -> wgpu::TextureFormat {
        if self
            .device
            .features()
            .contains(wgpu::Features::DEPTH32FLOAT_STENCIL8)
        {
            wgpu::TextureFormat::Depth32FloatStencil8
        } else {
            wgpu::TextureFormat::Depth24PlusStencil8
        }
    }

    /// Whether primitives can skip depth clipping (depth clamp), which keeps the caps of
    /// shadow volumes at infinity from being clipped at the far plane.
    pub fn has_depth_clamp(&self) -> bool {
        self.device
            .features()
            .contains(wgpu::Features::DEPTH_CLIP_CONTROL)
    }

    /// A uniform buffer holding `value`.
    pub fn uniform_buffer<T: bytemuck::Pod>(&self, label: &str, value: &T) -> wgpu::Buffer {
        self.buffer_with(
            label,
            bytemuck::bytes_of(value),
            wgpu::BufferUsages::UNIFORM,
        )
    }

    /// A buffer for `usage` holding `contents`.
    pub fn buffer_with(
        &self,
        label: &str,
        contents: &[u8],
        usage: wgpu::BufferUsages,
    ) -> wgpu::Buffer {
        use wgpu::util::DeviceExt;
        self.device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage,
            })
    }

    /// A storage buffer of `size` bytes the GPU writes and the CPU can read back.
    pub fn output_buffer(&self, label: &str, size: u64) -> wgpu::Buffer {
        self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        })
    }

    /// Runs one compute dispatch of `pipeline` with `bind` as group 0, then reads
    /// `output` back as `f32`s.
    pub fn dispatch_and_read(
        &self,
        pipeline: &wgpu::ComputePipeline,
        bind: &wgpu::BindGroup,
        workgroups: [u32; 3],
        output: &wgpu::Buffer,
    ) -> Result<Vec<f32>, GpuError> {
        let mut enc = self.device.create_command_encoder(&Default::default());
        {
            let mut pass = enc.begin_compute_pass(&Default::default());
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, bind, &[]);
            pass.dispatch_workgroups(workgroups[0], workgroups[1], workgroups[2]);
        }
        self.queue.submit([enc.finish()]);
        self.read_f32(output)
    }

    /// A bind group of `(binding, resource)` pairs.
    pub fn bind_group(
        &self,
        label: &str,
        layout: &wgpu::BindGroupLayout,
        entries: &[(u32, wgpu::BindingResource<'_>)],
    ) -> wgpu::BindGroup {
        let entries: Vec<wgpu::BindGroupEntry<'_>> = entries
            .iter()
            .map(|(binding, resource)| wgpu::BindGroupEntry {
                binding: *binding,
                resource: resource.clone(),
            })
            .collect();
        self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(label),
            layout,
            entries: &entries,
        })
    }

    /// A render pipeline that draws one full-screen triangle (no vertex buffers, layout
    /// from the shader) with the entry points `vs` and `fs` of `module` into `format`: the
    /// tone-mapping passes and the Catmull-Rom tables.
    pub fn fullscreen_pipeline(
        &self,
        label: &str,
        module: &wgpu::ShaderModule,
        (vs, fs): (&str, &str),
        format: wgpu::TextureFormat,
    ) -> wgpu::RenderPipeline {
        self.device
            .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(label),
                layout: None,
                vertex: wgpu::VertexState {
                    module,
                    entry_point: Some(vs),
                    compilation_options: Default::default(),
                    buffers: &[],
                },
                primitive: Default::default(),
                depth_stencil: None,
                multisample: Default::default(),
                fragment: Some(wgpu::FragmentState {
                    module,
                    entry_point: Some(fs),
                    compilation_options: Default::default(),
                    targets: &[Some(format.into())],
                }),
                multiview_mask: None,
                cache: None,
            })
    }

    /// A render pipeline drawing casters (`vertices`: position at location 0) with a
    /// written depth test (less) into `depth`, from the entry points `vs` and `fs` of
    /// `module`: the paraboloid shadow maps and the radiosity visibility maps.
    #[allow(clippy::too_many_arguments)]
    pub fn caster_depth_pipeline(
        &self,
        label: &str,
        layout: &wgpu::PipelineLayout,
        module: &wgpu::ShaderModule,
        (vs, fs): (&str, &str),
        vertices: wgpu::VertexBufferLayout<'_>,
        depth: wgpu::TextureFormat,
        targets: &[Option<wgpu::ColorTargetState>],
    ) -> wgpu::RenderPipeline {
        self.device
            .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(label),
                layout: Some(layout),
                vertex: wgpu::VertexState {
                    module,
                    entry_point: Some(vs),
                    compilation_options: Default::default(),
                    buffers: &[Some(vertices)],
                },
                primitive: wgpu::PrimitiveState::default(),
                depth_stencil: Some(wgpu::DepthStencilState {
                    format: depth,
                    depth_write_enabled: Some(true),
                    depth_compare: Some(wgpu::CompareFunction::Less),
                    stencil: Default::default(),
                    bias: Default::default(),
                }),
                multisample: Default::default(),
                fragment: Some(wgpu::FragmentState {
                    module,
                    entry_point: Some(fs),
                    compilation_options: Default::default(),
                    targets,
                }),
                multiview_mask: None,
                cache: None,
            })
    }

    /// "name (backend, device type)" of the adapter.
    pub fn describe(&self) -> String {
        let i = self.adapter.get_info();
        format!("{} ({:?}, {:?})", i.name, i.backend, i.device_type)
    }

    /// Copies `buffer` (which must allow COPY_SRC) back to the CPU as `f32`s.
    pub fn read_f32(&self, buffer: &wgpu::Buffer) -> Result<Vec<f32>, GpuError> {
        let bytes = self.read_bytes(buffer, |_| {})?;
        Ok(bytemuck::pod_collect_to_vec(&bytes))
    }

    /// Copies the first `bytes` bytes of `buffer` (which must allow COPY_SRC; a multiple
    /// of 4, at most its size) back to the CPU as `f32`s.
    pub fn read_f32_prefix(&self, buffer: &wgpu::Buffer, bytes: u64) -> Result<Vec<f32>, GpuError> {
        let bytes = self.read_bytes_prefix(buffer, bytes.min(buffer.size()), |_| {})?;
        Ok(bytemuck::pod_collect_to_vec(&bytes))
    }

    /// Copies `buffer` (which must allow COPY_SRC) back to the CPU as `u32`s.
    pub fn read_u32(&self, buffer: &wgpu::Buffer) -> Result<Vec<u32>, GpuError> {
        let bytes = self.read_bytes(buffer, |_| {})?;
        Ok(bytemuck::pod_collect_to_vec(&bytes))
    }

    /// An error when reading back a `width` × `height` image of `bytes` bytes would need a
    /// buffer larger than the device allows (a [`GpuError::Limit`]: refuse before the work).
    pub fn check_read_back(&self, width: u32, height: u32, bytes: u64) -> Result<(), GpuError> {
        let max = self.device.limits().max_buffer_size;
        if bytes > max {
            return Err(GpuError::Limit(format!(
                "reading back a {width}×{height} image takes {} MB, more than the {} MB this device's buffers hold: use a smaller image",
                bytes >> 20,
                max >> 20
            )));
        }
        Ok(())
    }

    /// Copies a whole 2D texture (which must allow COPY_SRC) back to the CPU, rows packed,
    /// layer after layer for an array.
    pub fn read_texture(&self, texture: &wgpu::Texture) -> Result<Vec<u8>, GpuError> {
        let (w, h) = (texture.width(), texture.height());
        let layers = texture.depth_or_array_layers();
        let texel = texture
            .format()
            .block_copy_size(None)
            .ok_or_else(|| GpuError::Operation("texture format cannot be copied".into()))?;
        let row = w * texel;
        let padded =
            row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
        let size = u64::from(padded) * u64::from(h) * u64::from(layers);
        self.check_read_back(w, h, size)?;
        let buffer = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("texture read-back"),
            size,
            usage: wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let bytes = self.read_bytes(&buffer, |enc| {
            enc.copy_texture_to_buffer(
                texture.as_image_copy(),
                wgpu::TexelCopyBufferInfo {
                    buffer: &buffer,
                    layout: wgpu::TexelCopyBufferLayout {
                        offset: 0,
                        bytes_per_row: Some(padded),
                        rows_per_image: Some(h),
                    },
                },
                texture.size(),
            );
        })?;
        let mut out = Vec::with_capacity((row * h * layers) as usize);
        for y in 0..(h * layers) as usize {
            let at = y * padded as usize;
            out.extend_from_slice(&bytes[at..at + row as usize]);
        }
        Ok(out)
    }

    /// Reads one texel (x, y) of a 2D texture back as its raw bytes (the lux read-out
    /// under the viewer's cursor).
    pub fn read_texel(&self, texture: &wgpu::Texture, x: u32, y: u32) -> Result<Vec<u8>, GpuError> {
        let texel = texture
            .format()
            .block_copy_size(None)
            .ok_or_else(|| GpuError::Operation("texture format cannot be copied".into()))?;
        if x >= texture.width() || y >= texture.height() {
            return Err(GpuError::Operation(format!(
                "texel ({x}, {y}) outside a {}×{} texture",
                texture.width(),
                texture.height()
            )));
        }
        let buffer = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("texel read-back"),
            size: wgpu::COPY_BYTES_PER_ROW_ALIGNMENT as u64,
            usage: wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut bytes = self.read_bytes(&buffer, |enc| {
            enc.copy_texture_to_buffer(
                wgpu::TexelCopyTextureInfo {
                    texture,
                    mip_level: 0,
                    origin: wgpu::Origin3d { x, y, z: 0 },
                    aspect: wgpu::TextureAspect::All,
                },
                wgpu::TexelCopyBufferInfo {
                    buffer: &buffer,
                    layout: wgpu::TexelCopyBufferLayout {
                        offset: 0,
                        bytes_per_row: None,
                        rows_per_image: None,
                    },
                },
                wgpu::Extent3d {
                    width: 1,
                    height: 1,
                    depth_or_array_layers: 1,
                },
            );
        })?;
        bytes.truncate(texel as usize);
        Ok(bytes)
    }

    /// Runs `before` (copies into `buffer`), then copies `buffer` to a mappable one and
    /// returns its bytes once the GPU is done.
    fn read_bytes(
        &self,
        buffer: &wgpu::Buffer,
        before: impl FnOnce(&mut wgpu::CommandEncoder),
    ) -> Result<Vec<u8>, GpuError> {
        self.read_bytes_prefix(buffer, buffer.size(), before)
    }

    /// Copies the first `size` bytes of `buffer` (which must allow COPY_SRC) back to the
    /// CPU, after recording `before` (a copy or query resolve into it) in the same
    /// submission.
    pub fn read_bytes_prefix(
        &self,
        buffer: &wgpu::Buffer,
        size: u64,
        before: impl FnOnce(&mut wgpu::CommandEncoder),
    ) -> Result<Vec<u8>, GpuError> {
        if size == 0 {
            return Ok(Vec::new());
        }
        let staging = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("read-back"),
            size,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut enc = self.device.create_command_encoder(&Default::default());
        before(&mut enc);
        enc.copy_buffer_to_buffer(buffer, 0, &staging, 0, size);
        self.queue.submit([enc.finish()]);
        let slice = staging.slice(..);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        self.wait()?;
        rx.recv()
            .map_err(|e| GpuError::Operation(e.to_string()))?
            .map_err(|e| GpuError::Operation(e.to_string()))?;
        let data = slice
            .get_mapped_range()
            .map_err(|e| GpuError::Operation(e.to_string()))?;
        let out = data.to_vec();
        drop(data);
        staging.unmap();
        Ok(out)
    }

    /// Blocks until the GPU has finished the submission `index` (and all before it).
    pub fn wait_for(&self, index: wgpu::SubmissionIndex) -> Result<(), GpuError> {
        self.device
            .poll(wgpu::PollType::Wait {
                submission_index: Some(index),
                timeout: None,
            })
            .map(|_| ())
            .map_err(|e| GpuError::Operation(e.to_string()))
    }

    /// Blocks until the GPU has finished all submitted work.
    pub fn wait(&self) -> Result<(), GpuError> {
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map(|_| ())
            .map_err(|e| GpuError::Operation(e.to_string()))
    }
}

/// The limits asked of a device: WebGPU's downlevel defaults (buffers of up to 256 MiB),
/// raised to what the adapter offers for texture sizes, storage buffers per stage (up to
/// 16; the radiosity solver binds
/// [`RADIOSITY_STORAGE_BUFFERS`](crate::render::limits::RADIOSITY_STORAGE_BUFFERS)) and the
/// size of one storage binding (lavapipe: 128 MiB; most GPUs: the whole buffer).
fn required_limits(adapter: &wgpu::Limits) -> wgpu::Limits {
    let defaults = wgpu::Limits::downlevel_defaults().using_resolution(adapter.clone());
    wgpu::Limits {
        max_storage_buffers_per_shader_stage: adapter.max_storage_buffers_per_shader_stage.min(16),
        max_storage_buffer_binding_size: adapter
            .max_storage_buffer_binding_size
            .min(defaults.max_buffer_size),
        ..defaults
    }
}

/// The vertex layout of bare positions (`Float32x3`, 12-byte stride, location 0).
pub const POSITION_LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: 12,
    step_mode: wgpu::VertexStepMode::Vertex,
    attributes: &wgpu::vertex_attr_array![0 => Float32x3],
};
