//! Reading accessors (glTF 2.0 §3.6.2): the elements of a buffer view, strided, and the values of
//! sparse accessors substituted; every byte range checked against its view and buffer, so that a
//! malformed file is an error naming the accessor, never a panic.

use std::path::Path;

use gltf::json::{self, accessor::ComponentType, accessor::Type};

use super::MAX_GLTF_TRIANGLES;
use super::buffers::BufferData;
use super::error::{GltfError, GltfObject, GltfObjectKind, GltfProblem};

/// The most elements read from one accessor: three vertices for each of
/// [`MAX_GLTF_TRIANGLES`], so that an accessor without a buffer view (all zeros but for its
/// sparse values) cannot ask for unbounded memory.
const MAX_ELEMENTS: u64 = 3 * MAX_GLTF_TRIANGLES;

/// Reads accessors of one document.
pub(super) struct Accessors<'a> {
    pub(super) root: &'a json::Root,
    pub(super) buffers: &'a BufferData<'a>,
    pub(super) path: &'a Path,
}

/// What an accessor must be for one use: its type and component types, and the name of the use
/// for messages.
struct Layout {
    used_as: &'static str,
    expected: &'static str,
    dimensions: usize,
    components: &'static [ComponentType],
}

impl<'a> Accessors<'a> {
    /// The accessor `index` as an object for messages.
    pub(super) fn object(&self, index: usize) -> GltfObject {
        let name = self
            .root
            .accessors
            .get(index)
            .and_then(|a| a.name.as_deref());
        GltfObject::new(GltfObjectKind::Accessor, index, name)
    }

    /// The element count of accessor `index`, without reading it.
    pub(super) fn count(&self, index: usize, context: &[GltfObject]) -> Result<usize, GltfError> {
        let accessor = self.accessor(index, context)?;
        self.checked_count(accessor.count.0, index, context)
    }

    /// The buffers accessor `index` reads, for loading them first.
    pub(super) fn buffers_of(&self, index: usize) -> Vec<usize> {
        let Some(accessor) = self.root.accessors.get(index) else {
            return Vec::new();
        };
        let mut views: Vec<usize> = accessor.buffer_view.iter().map(|v| v.value()).collect();
        if let Some(sparse) = &accessor.sparse {
            views.push(sparse.indices.buffer_view.value());
            views.push(sparse.values.buffer_view.value());
        }
        views
            .into_iter()
            .filter_map(|view| self.root.buffer_views.get(view))
            .map(|view| view.buffer.value())
            .collect()
    }

    /// A `VEC3` of `FLOAT` accessor (`POSITION`, `NORMAL`), used as `used_as`.
    pub(super) fn vec3(
        &self,
        index: usize,
        used_as: &'static str,
        context: &[GltfObject],
    ) -> Result<Vec<[f32; 3]>, GltfError> {
        let layout = Layout {
            used_as,
            expected: "VEC3 of FLOAT",
            dimensions: 3,
            components: &[ComponentType::F32],
        };
        self.read(index, &layout, context, |bytes| {
            std::array::from_fn(|k| {
                f32::from_le_bytes([
                    bytes[4 * k],
                    bytes[4 * k + 1],
                    bytes[4 * k + 2],
                    bytes[4 * k + 3],
                ])
            })
        })
    }

    /// An index accessor: `SCALAR` of `UNSIGNED_BYTE`, `UNSIGNED_SHORT` or `UNSIGNED_INT`.
    pub(super) fn indices(
        &self,
        index: usize,
        context: &[GltfObject],
    ) -> Result<Vec<u32>, GltfError> {
        let layout = Layout {
            used_as: "indices",
            expected: "SCALAR of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT",
            dimensions: 1,
            components: &[ComponentType::U8, ComponentType::U16, ComponentType::U32],
        };
        let size = self.component(index, context)?.size();
        self.read(index, &layout, context, |bytes| unsigned(&bytes[..size]))
    }

    fn accessor(
        &self,
        index: usize,
        context: &[GltfObject],
    ) -> Result<&'a json::Accessor, GltfError> {
        self.root
            .accessors
            .get(index)
            .ok_or_else(|| self.missing(context, "accessor"))
    }

    /// An index `gltf`'s validation should have refused: reported as invalid, not a panic.
    fn missing(&self, context: &[GltfObject], what: &str) -> GltfError {
        GltfError::Invalid {
            path: self.path.to_owned(),
            problems: vec![(
                context
                    .iter()
                    .map(ToString::to_string)
                    .collect::<Vec<_>>()
                    .join(": "),
                format!("{what} index out of bounds"),
            )],
        }
    }

    fn error(&self, index: usize, context: &[GltfObject], problem: GltfProblem) -> GltfError {
        let mut objects = context.to_vec();
        objects.push(self.object(index));
        GltfError::object(self.path, objects, problem)
    }

    /// The component type of accessor `index` (valid after `gltf`'s validation).
    fn component(&self, index: usize, context: &[GltfObject]) -> Result<ComponentType, GltfError> {
        match self.accessor(index, context)?.component_type {
            json::validation::Checked::Valid(component) => Ok(component.0),
            json::validation::Checked::Invalid => Err(self.missing(context, "componentType")),
        }
    }

    fn checked_count(
        &self,
        count: u64,
        index: usize,
        context: &[GltfObject],
    ) -> Result<usize, GltfError> {
        if count == 0 {
            return Err(self.error(index, context, GltfProblem::EmptyAccessor));
        }
        if count > MAX_ELEMENTS {
            return Err(GltfError::TooLarge {
                path: self.path.to_owned(),
                what: "elements in one accessor",
                count,
                limit: MAX_ELEMENTS,
            });
        }
        // At most MAX_ELEMENTS, far below usize::MAX.
        usize::try_from(count).map_err(|_| GltfError::TooLarge {
            path: self.path.to_owned(),
            what: "elements in one accessor",
            count,
            limit: MAX_ELEMENTS,
        })
    }

    /// The elements of accessor `index`, each decoded from its bytes by `decode`, after checking
    /// the accessor against `layout`.
    fn read<T: Copy + Default>(
        &self,
        index: usize,
        layout: &Layout,
        context: &[GltfObject],
        decode: impl Fn(&[u8]) -> T,
    ) -> Result<Vec<T>, GltfError> {
        let accessor = self.accessor(index, context)?;
        let component = self.component(index, context)?;
        let dimensions = match accessor.type_ {
            json::validation::Checked::Valid(kind) => kind,
            json::validation::Checked::Invalid => return Err(self.missing(context, "type")),
        };
        if dimensions.multiplicity() != layout.dimensions
            || !layout.components.contains(&component)
            || accessor.normalized
        {
            return Err(self.error(
                index,
                context,
                GltfProblem::WrongAccessorType {
                    used_as: layout.used_as,
                    expected: layout.expected,
                    found: format!(
                        "{}{} of {}",
                        if accessor.normalized {
                            "normalized "
                        } else {
                            ""
                        },
                        type_name(dimensions),
                        component_name(component)
                    ),
                },
            ));
        }
        let count = self.checked_count(accessor.count.0, index, context)?;
        let element = component.size() * layout.dimensions;
        let mut values = match accessor.buffer_view {
            Some(view) => {
                let offset = accessor.byte_offset.map_or(0, |o| o.0);
                let run =
                    self.view_run(view.value(), offset, count, element, true, index, context)?;
                run.map(&decode).collect()
            }
            None => vec![T::default(); count],
        };
        if let Some(sparse) = &accessor.sparse {
            let sparse_count = self.checked_count(sparse.count.0, index, context)?;
            let index_component = match sparse.indices.component_type {
                json::validation::Checked::Valid(component) => component.0,
                json::validation::Checked::Invalid => {
                    return Err(self.missing(context, "sparse.indices.componentType"));
                }
            };
            let index_size = index_component.size();
            let positions = self.view_run(
                sparse.indices.buffer_view.value(),
                sparse.indices.byte_offset.0,
                sparse_count,
                index_size,
                false,
                index,
                context,
            )?;
            let substitutes = self.view_run(
                sparse.values.buffer_view.value(),
                sparse.values.byte_offset.0,
                sparse_count,
                element,
                false,
                index,
                context,
            )?;
            let mut previous: Option<u32> = None;
            for (position, (index_bytes, value_bytes)) in positions.zip(substitutes).enumerate() {
                let target = unsigned(index_bytes);
                let slot = usize::try_from(target).ok().and_then(|t| values.get_mut(t));
                match slot {
                    Some(slot) if previous.is_none_or(|p| target > p) => {
                        *slot = decode(value_bytes);
                    }
                    _ => {
                        return Err(self.error(
                            index,
                            context,
                            GltfProblem::BadSparseIndex {
                                position,
                                index: u64::from(target),
                            },
                        ));
                    }
                }
                previous = Some(target);
            }
        }
        Ok(values)
    }

    /// The byte slices of `count` elements of `element` bytes in buffer view `view`, starting
    /// at `offset` within it, `byteStride` apart (tightly packed if the view has none, or if
    /// `strided` is false, as for sparse indices and values); every range checked.
    #[expect(
        clippy::too_many_arguments,
        reason = "one checked read of a view; the accessor and context only name it in errors"
    )]
    fn view_run(
        &self,
        view: usize,
        offset: u64,
        count: usize,
        element: usize,
        strided: bool,
        index: usize,
        context: &[GltfObject],
    ) -> Result<impl Iterator<Item = &'a [u8]>, GltfError> {
        let json_view = self
            .root
            .buffer_views
            .get(view)
            .ok_or_else(|| self.missing(context, "bufferView"))?;
        let view_object =
            GltfObject::new(GltfObjectKind::BufferView, view, json_view.name.as_deref());
        let buffer = json_view.buffer.value();
        let data: &'a [u8] = match self.buffers.get(buffer) {
            Some(Some(data)) => data,
            _ => return Err(self.missing(context, "buffer")),
        };
        let view_start = json_view.byte_offset.map_or(0, |o| o.0);
        let view_length = json_view.byte_length.0;
        let view_end = view_start.saturating_add(view_length);
        if view_end > data.len() as u64 {
            let mut objects = context.to_vec();
            objects.push(self.object(index));
            objects.push(view_object);
            return Err(GltfError::object(
                self.path,
                objects,
                GltfProblem::OutOfBounds {
                    what: "the buffer view's bytes",
                    start: view_start,
                    end: view_end,
                    length: data.len() as u64,
                },
            ));
        }
        let element_size = element as u64;
        let stride = match json_view.byte_stride {
            Some(stride) if strided => stride.0 as u64,
            _ => element_size,
        };
        if stride < element_size {
            return Err(self.error(
                index,
                context,
                GltfProblem::StrideTooSmall {
                    stride,
                    element: element_size,
                },
            ));
        }
        let end = (count as u64 - 1)
            .checked_mul(stride)
            .and_then(|span| span.checked_add(offset))
            .and_then(|span| span.checked_add(element_size))
            .unwrap_or(u64::MAX);
        if end > view_length {
            return Err(self.error(
                index,
                context,
                GltfProblem::OutOfBounds {
                    what: "the accessor's elements",
                    start: offset,
                    end,
                    length: view_length,
                },
            ));
        }
        // Every range below lies within data[view_start..view_end], checked above.
        let base = usize::try_from(view_start + offset).unwrap_or(usize::MAX);
        let stride = usize::try_from(stride).unwrap_or(usize::MAX);
        Ok((0..count).filter_map(move |k| {
            let start = base.checked_add(k.checked_mul(stride)?)?;
            data.get(start..start.checked_add(element)?)
        }))
    }
}

/// An unsigned little-endian integer of 1, 2 or 4 bytes.
fn unsigned(bytes: &[u8]) -> u32 {
    bytes
        .iter()
        .rev()
        .fold(0, |value, &byte| (value << 8) | u32::from(byte))
}

fn type_name(kind: Type) -> &'static str {
    match kind {
        Type::Scalar => "SCALAR",
        Type::Vec2 => "VEC2",
        Type::Vec3 => "VEC3",
        Type::Vec4 => "VEC4",
        Type::Mat2 => "MAT2",
        Type::Mat3 => "MAT3",
        Type::Mat4 => "MAT4",
    }
}

fn component_name(component: ComponentType) -> &'static str {
    match component {
        ComponentType::I8 => "BYTE",
        ComponentType::U8 => "UNSIGNED_BYTE",
        ComponentType::I16 => "SHORT",
        ComponentType::U16 => "UNSIGNED_SHORT",
        ComponentType::U32 => "UNSIGNED_INT",
        ComponentType::F32 => "FLOAT",
    }
}
