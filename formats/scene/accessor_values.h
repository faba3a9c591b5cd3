// Reading an AccessorData's elements as numbers, whatever its component
// type: what the algorithms, the reports and the writers' min/max need.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "formats/scene/scene.h"

namespace lodbake {

// Component `c` of element `i` as stored (an integer type's integer value).
// The caller keeps i < data.count and c < data.components(), and
// data.bytes.size() == data.count * data.element_size().
double stored_value(const AccessorData& data, size_t i, uint32_t c);

// The value a renderer sees: stored_value(), mapped to [0, 1] or [-1, 1]
// when the accessor is normalized (glTF 2.0 §3.11 rules: signed values
// clamp at -1).
float float_value(const AccessorData& data, size_t i, uint32_t c);

// Every element's components as float_value(), element by element.
std::vector<float> float_values(const AccessorData& data);

// The index buffer of a primitive as vertex numbers: its indices, or
// 0..vertex_count-1 for a non-indexed primitive.
std::vector<uint32_t> vertex_sequence(const ScenePrimitive& primitive);

// The primitive's triangles as vertex triples, counter-clockwise as glTF
// defines them: TRIANGLES as they come, TRIANGLE_STRIP and TRIANGLE_FAN
// unrolled with the specification's formulas (the zero-area stitching
// triangles that repeat an index are dropped). Points and lines give none.
std::vector<std::array<uint32_t, 3>> primitive_triangles(const ScenePrimitive& primitive);

}  // namespace lodbake
