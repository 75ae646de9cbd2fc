#pragma once
// Internal: bounds-checked reads of glTF accessors (byte offsets, strides, counts, component types,
// normalised integers, sparse substitution), every failure a GltfError with a JSON pointer.

#include <cstdint>
#include <string>
#include <vector>

#include "GltfDocument.h"

namespace throng::gltf {

/// Values of one accessor, widened to double or uint32, `width` per element.
template <class T>
struct AccessorValues {
    std::vector<T> values;  ///< count * width
    int width = 0;          ///< components per element
    std::size_t count = 0;  ///< elements
};

/// Reads accessors of one document; remembers which ones were read through a byte stride they
/// should not have, for one warning each.
class AccessorReader {
public:
    /// A reader of `doc` (which must outlive it).
    explicit AccessorReader(GltfDocument& doc, const GltfLimits& limits) : doc_(doc), limits_(limits) {}

    /// Checks that `index` names an accessor; `where` is the pointer of the reference.
    const tinygltf::Accessor& accessor(int index, const std::string& where) const;
    /// Reads accessor `index` as numbers (normalised integers mapped to [0, 1] or [-1, 1], other
    /// integers as they are). Types are checked by the caller. Non-finite values are errors.
    /// `vertexData`: false for data glTF does not allow a byte stride for (a stride is then read
    /// through with a warning).
    AccessorValues<double> readNumbers(int index, const std::string& where, bool vertexData = true);
    /// Reads accessor `index` of unsigned integer components (indices, joints).
    AccessorValues<std::uint32_t> readUnsigned(int index, const std::string& where);

private:
    template <class T>
    AccessorValues<T> read(int index, const std::string& where, bool integers, bool vertexData);
    // Whether accessor `index` was already warned about (and marks it).
    bool warnedStride(int index);
    GltfDocument& doc_;
    GltfLimits limits_;
    std::vector<int> warned_;
};

/// Components of an accessor type (SCALAR 1 ... MAT4 16), 0 if unknown.
int typeWidth(int type);

}  // namespace throng::gltf
