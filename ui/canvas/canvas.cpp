#include "ui/canvas/canvas.h"

#include <cairo-ft.h>
#include <cairo.h>
#include <ft2build.h>
#include FT_FREETYPE_H

#include <filesystem>
#include <mutex>
#include <stdexcept>

#include "core/util/data_files.h"

namespace ipd::ui {

PtRect text_box(Pt at, Anchor anchor, double w, double h) {
  double x = at.x, y = at.y;
  switch (anchor) {
    case Anchor::kTop:
    case Anchor::kCentre:
    case Anchor::kBottom:
      x -= w / 2;
      break;
    case Anchor::kTopRight:
    case Anchor::kRight:
    case Anchor::kBottomRight:
      x -= w;
      break;
    default:
      break;
  }
  switch (anchor) {
    case Anchor::kLeft:
    case Anchor::kCentre:
    case Anchor::kRight:
      y -= h / 2;
      break;
    case Anchor::kBottomLeft:
    case Anchor::kBottom:
    case Anchor::kBottomRight:
      y -= h;
      break;
    default:
      break;
  }
  return {x, y, x + w, y + h};
}

std::string default_font_file() {
  const std::string bundled = find_data_file("fonts/DejaVuSans.ttf", IPD_ASSETS_DIR);
  return bundled.empty() ? "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf" : bundled;
}

std::string font_file_problem(const std::string& font_file) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_type type = fs::status(font_file, ec).type();
  const char* what = nullptr;
  switch (type) {
    case fs::file_type::regular:
      return "";
    case fs::file_type::not_found:
      return font_file + ": no such font file";
    case fs::file_type::directory:
      what = "a directory";
      break;
    case fs::file_type::character:
      what = "a character device";
      break;
    case fs::file_type::block:
      what = "a block device";
      break;
    case fs::file_type::fifo:
      what = "a FIFO";
      break;
    case fs::file_type::socket:
      what = "a socket";
      break;
    default:  // none, unknown: it could not be examined (no permission on a folder above it, say)
      return font_file + ": cannot examine the font file: " + (ec ? ec.message() : std::string("unknown type"));
  }
  return font_file + ": is " + what + ", not a font file (expected a TrueType or OpenType font)";
}

namespace {

// One FreeType library for the process (FreeType faces must not outlive it); creating faces is serialised.
std::recursive_mutex ft_mutex;  // recursive: cairo may drop a face (and lock) while a face is being made
FT_Library ft_library() {
  static FT_Library lib = [] {
    FT_Library l = nullptr;
    if (FT_Init_FreeType(&l)) throw std::runtime_error("FreeType: cannot initialise");
    return l;
  }();
  return lib;
}

const cairo_user_data_key_t kFaceKey{};

cairo_font_face_t* load_face(const std::string& file, bool synthesize_bold) {
  std::lock_guard<std::recursive_mutex> lock(ft_mutex);
  FT_Face face = nullptr;
  if (FT_New_Face(ft_library(), file.c_str(), 0, &face))
    throw std::runtime_error(file + ": cannot read this font file (expected a TrueType or OpenType font)");
  cairo_font_face_t* cf = cairo_ft_font_face_create_for_ft_face(face, 0);
  // The FreeType face lives as long as cairo keeps the font face.
  cairo_font_face_set_user_data(cf, &kFaceKey, face, [](void* f) {
    std::lock_guard<std::recursive_mutex> l(ft_mutex);
    FT_Done_Face(static_cast<FT_Face>(f));
  });
  if (synthesize_bold) cairo_ft_font_face_set_synthesize(cf, CAIRO_FT_SYNTHESIZE_BOLD);
  return cf;
}

}  // namespace

struct FontMetrics::Impl {
  cairo_font_face_t* regular = nullptr;
  cairo_font_face_t* bold = nullptr;
  cairo_surface_t* surface = nullptr;
  cairo_t* cr = nullptr;
};

FontMetrics::FontMetrics(const std::string& font_file) : impl_(std::make_unique<Impl>()), file_(font_file) {
  if (const std::string problem = font_file_problem(font_file); !problem.empty()) throw std::runtime_error(problem);
  impl_->regular = load_face(font_file, false);
  // DejaVuSans.ttf -> DejaVuSans-Bold.ttf when it exists; otherwise an emboldened regular face.
  std::filesystem::path p(font_file);
  const std::filesystem::path bold = p.parent_path() / (p.stem().string() + "-Bold" + p.extension().string());
  std::error_code ec;
  if (std::filesystem::is_regular_file(bold, ec)) bold_file_ = bold.string();
  impl_->bold = bold_file_.empty() ? load_face(font_file, true) : load_face(bold_file_, false);
  impl_->surface = cairo_image_surface_create(CAIRO_FORMAT_A8, 1, 1);
  impl_->cr = cairo_create(impl_->surface);
  cairo_font_options_t* fo = cairo_font_options_create();
  cairo_font_options_set_hint_metrics(fo, CAIRO_HINT_METRICS_OFF);  // the same widths at every scale
  cairo_font_options_set_hint_style(fo, CAIRO_HINT_STYLE_NONE);
  cairo_set_font_options(impl_->cr, fo);
  cairo_font_options_destroy(fo);
}

FontMetrics::~FontMetrics() {
  cairo_destroy(impl_->cr);
  cairo_surface_destroy(impl_->surface);
  cairo_font_face_destroy(impl_->regular);
  cairo_font_face_destroy(impl_->bold);
}

void* FontMetrics::regular_face() const { return impl_->regular; }
void* FontMetrics::bold_face() const { return impl_->bold; }

Pt FontMetrics::measure(const TextStyle& style, const std::string& s) const {
  cairo_t* cr = impl_->cr;
  cairo_set_font_face(cr, style.bold ? impl_->bold : impl_->regular);
  cairo_set_font_size(cr, style.size_pt);
  cairo_font_extents_t fe;
  cairo_font_extents(cr, &fe);
  cairo_text_extents_t te;
  cairo_text_extents(cr, s.c_str(), &te);
  return {te.x_advance, fe.ascent + fe.descent};
}

double FontMetrics::ascent(const TextStyle& style) const {
  cairo_set_font_face(impl_->cr, style.bold ? impl_->bold : impl_->regular);
  cairo_set_font_size(impl_->cr, style.size_pt);
  cairo_font_extents_t fe;
  cairo_font_extents(impl_->cr, &fe);
  return fe.ascent;
}

// ---- DisplayList ----

namespace {
template <class Item, class Op>
Item make_item(Op op, std::vector<Pt> points = {}, PtRect r = {}, Colour colour = {}, double width = 0) {
  Item it;
  it.op = op;
  it.points = std::move(points);
  it.r = r;
  it.colour = colour;
  it.width = width;
  return it;
}
}  // namespace

void DisplayList::rect(const PtRect& r, Colour stroke, double w) {
  items_.push_back(make_item<Item>(Op::kRect, {}, r, stroke, w));
}
void DisplayList::fill_rect(const PtRect& r, Colour fill) {
  items_.push_back(make_item<Item>(Op::kFillRect, {}, r, fill));
}
void DisplayList::line(Pt a, Pt b, Colour colour, double w) {
  items_.push_back(make_item<Item>(Op::kLine, {a, b}, {}, colour, w));
}
void DisplayList::polyline(const std::vector<Pt>& points, Colour colour, double w, bool closed) {
  items_.push_back(make_item<Item>(Op::kPolyline, points, {}, colour, w));
  items_.back().closed = closed;
}
void DisplayList::circle(Pt c, double radius, Colour stroke, double w) {
  items_.push_back(make_item<Item>(Op::kCircle, {c}, {radius, 0, 0, 0}, stroke, w));
}
void DisplayList::fill_circle(Pt c, double radius, Colour fill) {
  items_.push_back(make_item<Item>(Op::kFillCircle, {c}, {radius, 0, 0, 0}, fill));
}
void DisplayList::text(Pt at, Anchor anchor, const TextStyle& style, const std::string& s) {
  Item it = make_item<Item>(Op::kText, {at}, {}, style.colour);
  it.anchor = anchor;
  it.style = style;
  it.s = s;
  items_.push_back(std::move(it));
}
void DisplayList::image(const FigurePicture& picture, const PtRect& where) {
  Item it = make_item<Item>(Op::kImage, {}, where);
  it.picture = picture;
  items_.push_back(std::move(it));
}
void DisplayList::push_clip(const PtRect& r) { items_.push_back(make_item<Item>(Op::kPushClip, {}, r)); }
void DisplayList::pop_clip() { items_.push_back(make_item<Item>(Op::kPopClip)); }

void DisplayList::replay(Canvas& out) const {
  for (const Item& it : items_) {
    switch (it.op) {
      case Op::kRect:
        out.rect(it.r, it.colour, it.width);
        break;
      case Op::kFillRect:
        out.fill_rect(it.r, it.colour);
        break;
      case Op::kLine:
        out.line(it.points[0], it.points[1], it.colour, it.width);
        break;
      case Op::kPolyline:
        out.polyline(it.points, it.colour, it.width, it.closed);
        break;
      case Op::kCircle:
        out.circle(it.points[0], it.r.x0, it.colour, it.width);
        break;
      case Op::kFillCircle:
        out.fill_circle(it.points[0], it.r.x0, it.colour);
        break;
      case Op::kText:
        out.text(it.points[0], it.anchor, it.style, it.s);
        break;
      case Op::kImage:
        out.image(it.picture, it.r);
        break;
      case Op::kPushClip:
        out.push_clip(it.r);
        break;
      case Op::kPopClip:
        out.pop_clip();
        break;
    }
  }
}

std::vector<DisplayList::TextItem> DisplayList::texts() const {
  std::vector<TextItem> out;
  for (const Item& it : items_)
    if (it.op == Op::kText) {
      const Pt m = metrics_.measure(it.style, it.s);
      out.push_back({text_box(it.points[0], it.anchor, m.x, m.y), it.s, it.style.size_pt});
    }
  return out;
}

}  // namespace ipd::ui
