// `ipd figure gallery`: crops of the rock pairs with the largest |perf_A - perf_B| of one model and domain
// pair across the study, A | B side by side, each crop with the GT box (solid yellow) and the rock's best
// prediction (dashed blue), the performance values and the scene and rock names; from the pictures when the
// study has them, on a plain background when it has labels only (the figure says which). The pairs and their
// order are the studio's Rock pairs gallery's (core/session/rock_pair_points.h).
#pragma once

#include <cmath>
#include <functional>

#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

#include "core/ipd/ipd.h"
#include "core/session/rock_pair_points.h"
#include "ui/canvas/canvas.h"
#include "ui/figures/figure_options.h"

namespace ipd::ui {

// One side of a pair: its GT rock, the rock's best-IoU prediction, and the region of the picture the crop
// shows (normalised, a square in pixels around the rock, 2.5 times its larger side; it may reach past the
// picture's edge, which shows as background).
struct GalleryCrop {
  int rock = -1;  // 0-based; printed from 1 as the studio numbers rocks
  // The right rock's pair as the pictures number it (by its left rock), when that is not its own number: printed
  // beside it, "rock 10 (pair 7)", as the studio's status line says it. -1: none (a left rock, or the same number).
  int pair = -1;
  double perf = 0;
  bool mask = false;  // perf is a mask IoU (task segment): said so under the crop
  // With a mask: the IoU of the GT's box with the box of the same prediction, printed beside the mask IoU so a
  // reader sees what the outline changes (NaN without a prediction or without masks).
  double box_iou = NAN;
  Box gt, pred;
  bool has_pred = false;
  Crop region;
  cv::Mat pixels;       // the part of the picture inside `region` (BGR), empty without a picture
  Crop covered;         // the normalised region `pixels` covers
  std::string problem;  // why a picture the study names could not be read
};

struct GalleryEntry {
  std::string stem;
  double diff = 0;
  GalleryCrop a, b;
};

struct GalleryInput {
  std::string a, b, model;
  GallerySort sort = GallerySort::kDiff;
  int counted_pairs = 0;  // in the cell: the entries are the first of these
  std::vector<GalleryEntry> entries;
  std::string scene;  // gallery_input's scene and rock, when the pairs were picked by them (the title says so)
  int rock = 0;
  bool pictures = false;  // load_gallery_pictures found a picture for some crop
};

// The region a crop shows: a square of pixels around `gt`, kContext (2.5) times its larger side and at least
// 16 px wide, in normalised coordinates of a w x h picture. The studio's gallery crops with it too, so its
// rocks keep their shape and read as the figure's.
Crop gallery_crop_region(const Box& gt, int w, int h);
// A crop's rock and its best prediction (null: none) in the gallery's styles: the prediction dashed on a light
// halo, the GT solid on a dark halo; an instance with an outline as its outline (the mask its performance value
// is about), else as its box. `at` maps normalised picture coordinates to the canvas. The figure and ipd-studio's
// gallery both draw through it, so the window previews the figure.
void draw_gallery_instances(Canvas& c, const std::function<Pt(double x, double y)>& at, const Box& gt, const Box* pred,
                            double stroke, double dash);
// The picture size crops are measured in: w x h when known (> 0), else the POLAR cameras' 1936 x 1216.
std::pair<int, int> gallery_picture_size(int w, int h);

// The first `count` counted pairs of `cell` in `sort` order (gallery_sorted), with their boxes. `labels`
// must be the ones the table was computed from (threshold applied).
// `scene` (optional): only that scene's pairs; `rock` (from 1, with a scene): only the pair of that rock of the
// cell's first domain, a figure of one rock pair. Throws StudyError naming the scene's paired rocks when the
// scene or rock is in no counted pair.
GalleryInput gallery_input(const StudyLabels& labels, const TableCell& cell, int count, GallerySort sort,
                           const std::string& scene = "", int rock = 0);

// Reads each scene's picture once and keeps only the crops (a picture that can't be decoded is named in the
// crop's problem). File I/O: off the UI thread.
void load_gallery_pictures(GalleryInput& in, const Study& study);

// Where each entry went (points), for tests.
struct GalleryLayout {
  std::vector<PtRect> left, right;
};
GalleryLayout draw_gallery_figure(DisplayList& out, const GalleryInput& in, const FigureOptions& options);

}  // namespace ipd::ui
