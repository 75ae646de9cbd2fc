#include "AccessorReader.h"

#include <cmath>
#include <cstring>
#include <type_traits>

#include "throng/gltf/GltfError.h"

namespace throng::gltf {
namespace {

int componentSize(int componentType) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
        default: return 0;  // INT and DOUBLE are not glTF 2.0 accessor types
    }
}

// One component at `p` (memcpy: glTF data need not be aligned in our copy of the buffer).
double component(const std::uint8_t* p, int type, bool normalized) {
    switch (type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            std::int8_t v;
            std::memcpy(&v, p, 1);
            return normalized ? std::max(v / 127.0, -1.0) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? *p / 255.0 : *p;
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            std::int16_t v;
            std::memcpy(&v, p, 2);
            return normalized ? std::max(v / 32767.0, -1.0) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            std::uint16_t v;
            std::memcpy(&v, p, 2);
            return normalized ? v / 65535.0 : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
            std::uint32_t v;
            std::memcpy(&v, p, 4);
            return normalized ? v / 4294967295.0 : v;
        }
        default: {
            float v;
            std::memcpy(&v, p, 4);
            return v;
        }
    }
}

}  // namespace

int typeWidth(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR: return 1;
        case TINYGLTF_TYPE_VEC2: return 2;
        case TINYGLTF_TYPE_VEC3: return 3;
        case TINYGLTF_TYPE_VEC4: return 4;
        case TINYGLTF_TYPE_MAT2: return 4;
        case TINYGLTF_TYPE_MAT3: return 9;
        case TINYGLTF_TYPE_MAT4: return 16;
        default: return 0;
    }
}

const tinygltf::Accessor& AccessorReader::accessor(int index, const std::string& where) const {
    if (index < 0 || static_cast<std::size_t>(index) >= doc_.model.accessors.size())
        throw GltfError(doc_.file, where, "accessor " + std::to_string(index) + " does not exist (" +
                                              std::to_string(doc_.model.accessors.size()) + " accessors)");
    return doc_.model.accessors[static_cast<std::size_t>(index)];
}

bool AccessorReader::warnedStride(int index) {
    for (int w : warned_)
        if (w == index) return true;
    warned_.push_back(index);
    return false;
}

AccessorValues<double> AccessorReader::readNumbers(int index, const std::string& where, bool vertexData) {
    return read<double>(index, where, false, vertexData);
}

AccessorValues<std::uint32_t> AccessorReader::readUnsigned(int index, const std::string& where) {
    return read<std::uint32_t>(index, where, true, true);
}

template <class T>
AccessorValues<T> AccessorReader::read(int index, const std::string& where, bool integers, bool vertexData) {
    const tinygltf::Accessor& a = accessor(index, where);
    const std::string self = "/accessors/" + std::to_string(index);
    const auto& m = doc_.model;
    const int width = typeWidth(a.type);
    const int size = componentSize(a.componentType);
    if (width == 0) throw GltfError(doc_.file, self + "/type", "unknown accessor type");
    if (size == 0) throw GltfError(doc_.file, self + "/componentType", "component type " + std::to_string(a.componentType) + " is not allowed");
    if (integers && (a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT || a.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
                     a.componentType == TINYGLTF_COMPONENT_TYPE_SHORT || a.normalized))
        throw GltfError(doc_.file, self + "/componentType", "must be an unsigned integer type here (read for " + where + ")");
    if ((a.type == TINYGLTF_TYPE_MAT2 || a.type == TINYGLTF_TYPE_MAT3) && size < 4)
        throw GltfError(doc_.file, self + "/componentType", "matrices of 1- or 2-byte components are not supported");
    if (a.count == 0) throw GltfError(doc_.file, self + "/count", "must be at least 1");
    if (a.count > limits_.maxAccessorValues / static_cast<std::uint64_t>(width))
        throw GltfError(doc_.file, self + "/count", std::to_string(a.count) + " elements exceed the limit of " +
                                                         std::to_string(limits_.maxAccessorValues) + " values per accessor");
    AccessorValues<T> out;
    out.width = width;
    out.count = a.count;
    out.values.assign(a.count * static_cast<std::size_t>(width), T(0));
    const std::uint64_t elementSize = std::uint64_t(size) * static_cast<std::uint64_t>(width);

    auto convert = [&](const std::uint8_t* p, std::size_t slot, const std::string& at) {
        const double v = component(p, a.componentType, a.normalized);
        if constexpr (std::is_same_v<T, double>) {
            if (!std::isfinite(v)) throw GltfError(doc_.file, at, "value " + std::to_string(slot) + " is not finite");
            out.values[slot] = v;
        } else {
            out.values[slot] = static_cast<T>(v);
        }
    };
    // Reads `count` elements of a view at byte `offset` into element slots given by `slotOf`.
    auto readView = [&](int viewIndex, std::uint64_t offset, std::uint64_t stride, std::size_t count,
                        std::uint64_t elemSize, const std::string& at, auto&& each) {
        if (viewIndex < 0 || static_cast<std::size_t>(viewIndex) >= m.bufferViews.size())
            throw GltfError(doc_.file, at + "/bufferView", "buffer view " + std::to_string(viewIndex) + " does not exist");
        const tinygltf::BufferView& v = m.bufferViews[static_cast<std::size_t>(viewIndex)];
        if (v.byteStride != 0) {
            if (!vertexData && !warnedStride(index))
                doc_.warnings.push_back(self + ": buffer view " + std::to_string(viewIndex) + " has a byteStride (" +
                                        std::to_string(v.byteStride) + ") glTF forbids for this use (" + where +
                                        "); read through it");
            stride = v.byteStride;
            if (stride < elemSize)
                throw GltfError(doc_.file, "/bufferViews/" + std::to_string(viewIndex) + "/byteStride",
                                "stride " + std::to_string(stride) + " is smaller than an element (" + std::to_string(elemSize) + " bytes)");
        }
        const std::uint64_t end = offset + stride * (count - 1) + elemSize;
        if (end > v.byteLength)
            throw GltfError(doc_.file, at, "reads bytes up to " + std::to_string(end) + " of buffer view " +
                                               std::to_string(viewIndex) + " which holds " + std::to_string(v.byteLength));
        const std::uint8_t* base = m.buffers[static_cast<std::size_t>(v.buffer)].data.data() + v.byteOffset + offset;
        for (std::size_t e = 0; e < count; ++e) each(e, base + e * stride);
    };

    if (a.bufferView >= 0) {
        readView(a.bufferView, a.byteOffset, elementSize, a.count, elementSize, self, [&](std::size_t e, const std::uint8_t* p) {
            for (int c = 0; c < width; ++c) convert(p + c * size, e * width + static_cast<std::size_t>(c), self);
        });
    }
    if (a.sparse.isSparse) {
        const std::string sp = self + "/sparse";
        if (a.sparse.count < 1 || static_cast<std::size_t>(a.sparse.count) > a.count)
            throw GltfError(doc_.file, sp + "/count", "must lie in [1, " + std::to_string(a.count) + "]");
        const auto n = static_cast<std::size_t>(a.sparse.count);
        const int it = a.sparse.indices.componentType;
        if (it != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && it != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            it != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
            throw GltfError(doc_.file, sp + "/indices/componentType", "must be an unsigned integer type");
        if (a.sparse.indices.byteOffset < 0 || a.sparse.values.byteOffset < 0)
            throw GltfError(doc_.file, sp, "a byteOffset is negative");
        std::vector<std::size_t> targets(n);
        const std::uint64_t isz = std::uint64_t(componentSize(it));
        readView(a.sparse.indices.bufferView, std::uint64_t(a.sparse.indices.byteOffset), isz, n, isz, sp + "/indices",
                 [&](std::size_t e, const std::uint8_t* p) {
                     const auto target = static_cast<std::uint64_t>(component(p, it, false));
                     if (target >= a.count)
                         throw GltfError(doc_.file, sp + "/indices", "index " + std::to_string(target) + " (entry " +
                                                                         std::to_string(e) + ") is not below count " + std::to_string(a.count));
                     if (e > 0 && target <= targets[e - 1])
                         throw GltfError(doc_.file, sp + "/indices", "indices are not strictly increasing at entry " + std::to_string(e));
                     targets[e] = static_cast<std::size_t>(target);
                 });
        readView(a.sparse.values.bufferView, std::uint64_t(a.sparse.values.byteOffset), elementSize, n, elementSize,
                 sp + "/values", [&](std::size_t e, const std::uint8_t* p) {
                     for (int c = 0; c < width; ++c)
                         convert(p + c * size, targets[e] * width + static_cast<std::size_t>(c), sp + "/values");
                 });
    }
    return out;
}

}  // namespace throng::gltf
