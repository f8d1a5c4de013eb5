// The paper's figures, drawn into an ImDrawList of a given size: the headless renderer (OSMesa) uses them,
// and so does the GUI through it ("Export figure" runs `ipd figure`).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "ipd/geometry.h"
#include "ipd/registration.h"
#include "scene_canvas.h"

namespace ipd::ui {

// Fig. 1: two pictures side by side under a title line.
struct PairsFigure {
  std::string title;
  SideInput left, right;
};
struct PairsLayout {
  float title_height;
  ImVec2 left_min, right_min, side_size;
};
PairsLayout pairs_layout(ImVec2 size, float font_px);
void draw_pairs_figure(ImDrawList* dl, ImVec2 size, float font_px, const PairsFigure& fig);
// The height the figure needs for a given width (pictures keep their aspect ratio).
float pairs_figure_height(float width, float font_px, int image_w, int image_h);

// Fig. 2: GT centres before and after registration, lines between partners, a legend.
struct RegistrationFigure {
  std::string title, name_a, name_b;
  std::vector<Eigen::Vector2d> a, b;  // normalised centres
  Affine2 affine = identity_affine();  // A -> B
  RockPairs pairs;
  int image_w = 1936, image_h = 1216;
};
void draw_registration_figure(ImDrawList* dl, ImVec2 size, float font_px, const RegistrationFigure& fig);
float registration_figure_height(float width, float font_px, int image_w, int image_h);

// Table I as a picture.
struct TableFigure {
  std::string title;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::vector<std::vector<char>> bold;  // per cell (rows x header), the row's best
  std::string note;
};
void draw_table_figure(ImDrawList* dl, ImVec2 size, float font_px, const TableFigure& fig);
float table_figure_height(float font_px, const TableFigure& fig);

}  // namespace ipd::ui
