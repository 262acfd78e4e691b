#pragma once
/// @file Closed, welded, outward-wound meshes of simple solids, and ways to combine them.
///
/// Every builder returns a watertight mesh: each undirected edge is shared by exactly two
/// triangles that traverse it in opposite directions, no triangle is degenerate and the signed
/// volume is positive. Builders throw std::invalid_argument on bad parameters (a non-positive
/// size, too few segments, a profile that leaves the axis in the wrong place).

#include <Eigen/Core>
#include <array>
#include <vector>

#include "engine/geometry/triangle_mesh.hpp"

namespace tumble::engine {

/// Axis-aligned box of edge lengths `size` (m), centred at the origin: 8 vertices, 12 triangles.
TriangleMesh box_mesh(const Eigen::Vector3d& size);

/// Tetrahedron on four non-coplanar corners, wound outward whatever their order.
TriangleMesh tetrahedron_mesh(const std::array<Eigen::Vector3d, 4>& corners);

/// Latitude-longitude sphere centred at the origin: `segments` (>= 3) around the z axis,
/// `rings` (>= 2) latitude bands from pole to pole, each pole a single vertex.
TriangleMesh uv_sphere_mesh(double radius, int segments, int rings);

/// The latitude-longitude sphere scaled by `radii` along x, y and z.
TriangleMesh ellipsoid_mesh(const Eigen::Vector3d& radii, int segments, int rings);

/// Prism on a regular `segments`-gon inscribed in a circle of `radius`, axis z, centred at the
/// origin (z in [-height/2, height/2]); each cap is a fan around a centre vertex.
TriangleMesh cylinder_mesh(double radius, double height, int segments);

/// Pyramid on a regular `segments`-gon inscribed in a circle of `radius`: base at z = 0
/// (a fan around a centre vertex), apex at z = `height`.
TriangleMesh cone_mesh(double radius, double height, int segments);

/// Torus about the z axis: tube of `minor_radius` whose centre circle has `major_radius`,
/// with `major_segments` around the axis and `minor_segments` around the tube (both >= 3).
TriangleMesh torus_mesh(double major_radius, double minor_radius, int major_segments,
                        int minor_segments);

/// Solid of revolution about the z axis of the polyline `profile_rz` of (r, z) points. The first
/// and last points must lie on the axis (r = 0) and become single apex vertices; the points in
/// between must have r > 0. Either direction of travel is accepted. Each ring is a regular
/// `segments`-gon, so every band is a planar trapezoid strip.
TriangleMesh revolve_profile(const std::vector<Eigen::Vector2d>& profile_rz, int segments);

/// Prism of the simple polygon `outline_xy` (either orientation, convex or not) between the
/// planes z = `z0` and z = `z1`; the caps are triangulated by ear clipping. Collinear outline
/// points are kept (they stay vertices of the side walls and the caps).
TriangleMesh extrude_polygon(const std::vector<Eigen::Vector2d>& outline_xy, double z0, double z1);

/// Sphere from an icosahedron whose triangles are split in four `subdivisions` times, every
/// vertex pushed onto the sphere: 20 * 4^subdivisions triangles.
TriangleMesh icosphere_mesh(double radius, int subdivisions);

/// Appends `part` to `into` as a separate set of vertices and triangles.
void append_mesh(TriangleMesh& into, const TriangleMesh& part);

/// Maps every vertex x to `linear` x + `translation`. A mirroring map (det < 0) reverses each
/// triangle's winding so the mesh stays outward-wound.
void transform_mesh(TriangleMesh& mesh, const Eigen::Matrix3d& linear,
                    const Eigen::Vector3d& translation);

}  // namespace tumble::engine
