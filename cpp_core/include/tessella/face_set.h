// FaceSet: several trimmed faces panelized as one envelope (a shell, a solid,
// a compound, faces picked one by one), and panelize_faces(): every face runs
// the pipeline, and along an edge two faces share their nodes agree (one node
// at each position, one rod per segment, no T-junction).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "tessella/panelize.h"

namespace tessella {

class FaceSet {
 public:
  // Every face of the shape, in OCCT's explorer order (a face met twice, as
  // in a compound holding it twice, once), but faces that enclose no area
  // (slits a STEP exporter left between two faces: skipped()). Faces that
  // touch along edges they do not share (faces of several objects, an
  // unsewn STEP shell, the two sides of a slit left out) are sewn first, so
  // those edges are shared (sewn() tells). Throws InvalidGeometry for a
  // shape without faces, a face that cannot be evaluated (naming it: "face
  // 3: ...", numbered as given) or a shape of no face with an area.
  static FaceSet from_brep_string(const std::string& brep);

  // The faces panelized (the faces given but those skipped).
  std::size_t size() const;
  // Face i (its own copy of the geometry: threads evaluate faces side by side).
  std::shared_ptr<const SurfaceFace> face(std::size_t i) const;
  // How many faces the shape has, and face i's index among them (0-based):
  // results and messages name faces as given.
  std::size_t given_count() const;
  int given_index(std::size_t i) const;
  // The faces left out, by their index as given, and why.
  struct Skipped {
    int face = 0;
    std::string why;
  };
  const std::vector<Skipped>& skipped() const;
  // Edges bounding exactly two different faces of the set.
  std::size_t shared_edge_count() const;
  // Whether faces were sewn along edges they did not share.
  bool sewn() const;

  struct Impl;
  const Impl& impl() const { return *impl_; }

 private:
  explicit FaceSet(std::shared_ptr<Impl> impl);
  std::shared_ptr<Impl> impl_;
};

// Face indices in a result (panel_face, face_summaries, ...) and in its
// messages are the faces' as given (FaceSet::given_index).
struct FaceSetResult {
  // All faces' panels in one mesh (face order, then each face's own order),
  // welded along the shared edges; `face` is null, the summary adds up the
  // faces' (statistics over all panels and rods).
  PanelizeResult combined;
  // The source face of every panel, vertex (its first face along a shared
  // edge) and rod (the lower face of a rod on a shared edge).
  std::vector<int> panel_face, vertex_face, rod_face;
  // Each face's own summary (its panels before the faces were joined).
  std::vector<PanelizeSummary> face_summaries;
  int shared_edges = 0;
  // Nodes on shared edges, counted once; how many of them one face had and
  // the other took over (inserted into its outline or moved onto it).
  int shared_edge_nodes = 0, shared_nodes_taken_over = 0;
  // Checked on the joined result: segments between consecutive nodes along
  // shared edges, and those without a side of one panel of each face (a
  // T-junction or a gap: parts that will not fit), with a warning saying
  // where the first is ("" when none).
  int shared_edge_segments = 0, unmatched_shared_segments = 0;
  std::string join_warning;
  // Faces laid out on the union of faces lying on one surface, so that the
  // layout runs on across the edges between them: boundary_driven's curves
  // traced there, walking_agent's lines walked there.
  int faces_traced_across = 0;
  // boundary_driven: faces on different surfaces, joined by smooth edges,
  // meshed from curves traced across them (bd_across_surfaces.h).
  int faces_traced_across_surfaces = 0;
  // boundary_driven: per face, the smaller size it was meshed at where the
  // set's size is too coarse for its openings and notches (a small face of a
  // STEP part), else 0.
  std::vector<double> smaller_size;
  // The faces the set left out (FaceSet::skipped): no panel, an empty summary.
  std::vector<FaceSet::Skipped> skipped;
  // boundary_driven: faces whose share of the curves traced across faces
  // failed the final check, meshed from their own curves instead.
  std::vector<int> retraced_alone;
};

// The pipeline on every face of `set` (faces side by side on `threads`
// threads, 0: TESSELLA_THREADS or every core; the same result for any count),
// then joined. Methods that take guide curves or a start point refer to one
// face and are refused for more than one face.
FaceSetResult panelize_faces(const FaceSet& set, const std::string& method,
                             const ParamValues& values = {}, int threads = 0);

}  // namespace tessella
