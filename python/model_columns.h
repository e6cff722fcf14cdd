// A COLMAP model as numpy columns: cameras, images (poses and names), their 2-D points and the
// 3-D points, each a dict of arrays that comic/__init__.py packs into structured arrays.
#pragma once

#include <pybind11/pybind11.h>

#include "io/colmap/colmap_text_model.h"

namespace comic::python {

namespace py = pybind11;

// {"cameras", "images", "points2D", "points3D"}, each a dict of columns.
py::dict ModelToColumns(const io::ColmapTextModel& model);

}  // namespace comic::python
