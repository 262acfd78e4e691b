#pragma once
/// @file A primitive shape as scene files (and robot files) write it: one key naming the kind.
///
///   {"box": [x, y, z]}                          full edge lengths, m
///   {"sphere": {"radius": r}}
///   {"cylinder": {"radius": r, "length": l}}    axis z, l end to end
///   {"capsule": {"radius": r, "length": l}}     l the cylindrical part only
///   {"ellipsoid": [a, b, c]}                    semi-axes along x, y, z
///   {"cone": {"radius": r, "height": h}}        base at z = -h/4, centre of mass the origin
///
/// Conventions and formulas: engine/include/engine/primitive_shapes.hpp, engine/PHYSICS.md §9.

#include "app/scene/json_field.hpp"
#include "engine/mass/primitive_shapes.hpp"

namespace tumble::app {

/// Reads and validates a shape: exactly one known kind, its members all present, known and
/// positive numbers, and a volume and moments a double can hold. Throws tumble::InputError
/// "FILE: PATH.kind.member: expected ..." (unknown keys and wrong types as JsonField does).
engine::Shape parse_shape(const JsonField& field);

}  // namespace tumble::app
