#pragma once
// The face each surface voxel of a voxmap and each point of a point shell lies on
// (mesh/analytic_faces.h face_at): the hybrid's "voxel data expansion" (seed 002 section
// 5.2, Figs. 20-21), so that colliding voxel / point pairs name the faces in contact.
#include <cstdint>
#include <vector>

#include "mesh/analytic_faces.h"
#include "scheduler/vps/voxmap.h"

namespace snapfit {

// Labels of the surface layer of a voxmap (kNoFace for every other voxel), one per voxel
// in the map's order, from the voxel centres: tolerance one voxel, edge band half a voxel
// (a face that passes within half a voxel of the centre crosses the voxel's core).
std::vector<std::int16_t> label_voxmap(const Voxmap& map, const std::vector<AnalyticFace>& faces);

// Labels of the points of a point shell, which lie on the surface: tolerance one
// spacing, edge band half the spacing (as for voxels: a rim point that can sit inside the
// other part's surface voxels along the adjacent face is on the edge).
std::vector<std::int16_t> label_point_shell(const PointShell& shell, const std::vector<AnalyticFace>& faces);

}  // namespace snapfit
