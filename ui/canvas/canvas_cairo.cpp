#include "ui/canvas/canvas_cairo.h"
#include "ui/canvas/png_text.h"

#include <cairo-pdf.h>
#include <cairo.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "ui/canvas/canvas_svg.h"

namespace ipd::ui {

std::optional<FigureFormat> figure_format_of(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".pdf") return FigureFormat::kPdf;
  if (ext == ".svg") return FigureFormat::kSvg;
  if (ext == ".png") return FigureFormat::kPng;
  return std::nullopt;
}

const char* to_string(FigureFormat f) {
  return f == FigureFormat::kPdf ? "pdf" : f == FigureFormat::kSvg ? "svg" : "png";
}

namespace {

class CairoCanvas : public Canvas {
 public:
  // `raster`: an image surface (pictures are resampled, their edges padded); otherwise a PDF, where pictures
  // go in with their own pixels.
  CairoCanvas(cairo_t* cr, const FontMetrics& m, bool raster) : cr_(cr), metrics_(m), raster_(raster) {
    cairo_font_options_t* fo = cairo_font_options_create();
    cairo_font_options_set_hint_metrics(fo, CAIRO_HINT_METRICS_OFF);  // as measured
    cairo_font_options_set_hint_style(fo, CAIRO_HINT_STYLE_NONE);
    cairo_font_options_set_antialias(fo, CAIRO_ANTIALIAS_GRAY);
    cairo_set_font_options(cr_, fo);
    cairo_font_options_destroy(fo);
  }
  void rect(const PtRect& r, Colour c, double w) override {
    cairo_rectangle(cr_, r.x0, r.y0, r.width(), r.height());
    stroke(c, w);
  }
  void fill_rect(const PtRect& r, Colour c) override {
    cairo_rectangle(cr_, r.x0, r.y0, r.width(), r.height());
    set(c);
    cairo_fill(cr_);
  }
  void line(Pt a, Pt b, Colour c, double w) override {
    cairo_move_to(cr_, a.x, a.y);
    cairo_line_to(cr_, b.x, b.y);
    stroke(c, w);
  }
  void polyline(const std::vector<Pt>& pts, Colour c, double w, bool closed) override {
    if (pts.empty()) return;
    cairo_move_to(cr_, pts[0].x, pts[0].y);
    for (size_t i = 1; i < pts.size(); ++i) cairo_line_to(cr_, pts[i].x, pts[i].y);
    if (closed) cairo_close_path(cr_);
    stroke(c, w);
  }
  void circle(Pt c, double r, Colour col, double w) override {
    cairo_new_sub_path(cr_);
    cairo_arc(cr_, c.x, c.y, r, 0, 2 * M_PI);
    stroke(col, w);
  }
  void fill_circle(Pt c, double r, Colour col) override {
    cairo_new_sub_path(cr_);
    cairo_arc(cr_, c.x, c.y, r, 0, 2 * M_PI);
    set(col);
    cairo_fill(cr_);
  }
  void text(Pt at, Anchor anchor, const TextStyle& st, const std::string& s) override {
    const Pt m = metrics_.measure(st, s);
    const PtRect box = text_box(at, anchor, m.x, m.y);
    cairo_set_font_face(cr_, static_cast<cairo_font_face_t*>(st.bold ? metrics_.bold_face() : metrics_.regular_face()));
    cairo_set_font_size(cr_, st.size_pt);
    set(st.colour);
    cairo_move_to(cr_, box.x0, box.y0 + metrics_.ascent(st));
    cairo_show_text(cr_, s.c_str());
    cairo_new_path(cr_);
  }
  void image(const FigurePicture& p, const PtRect& where) override {
    if (p.pixels.empty()) return;
    cv::Mat bgra;
    cv::cvtColor(p.pixels, bgra, p.pixels.channels() == 1 ? cv::COLOR_GRAY2BGRA : cv::COLOR_BGR2BGRA);
    // cairo's ARGB32 is B, G, R, A in memory on little-endian machines: OpenCV's BGRA.
    cairo_surface_t* img = cairo_image_surface_create(CAIRO_FORMAT_RGB24, bgra.cols, bgra.rows);
    cairo_surface_flush(img);
    unsigned char* dst = cairo_image_surface_get_data(img);
    const int stride = cairo_image_surface_get_stride(img);
    for (int y = 0; y < bgra.rows; ++y) std::copy_n(bgra.ptr<unsigned char>(y), bgra.cols * 4, dst + y * stride);
    cairo_surface_mark_dirty(img);
    cairo_save(cr_);
    cairo_rectangle(cr_, where.x0, where.y0, where.width(), where.height());
    cairo_clip(cr_);
    cairo_translate(cr_, where.x0, where.y0);
    cairo_scale(cr_, where.width() / bgra.cols, where.height() / bgra.rows);
    cairo_set_source_surface(cr_, img, 0, 0);
    cairo_pattern_set_filter(cairo_get_source(cr_), CAIRO_FILTER_GOOD);
    if (raster_) cairo_pattern_set_extend(cairo_get_source(cr_), CAIRO_EXTEND_PAD);
    cairo_paint(cr_);
    cairo_restore(cr_);
    cairo_surface_destroy(img);
  }
  void push_clip(const PtRect& r) override {
    cairo_save(cr_);
    cairo_rectangle(cr_, r.x0, r.y0, r.width(), r.height());
    cairo_clip(cr_);
  }
  void pop_clip() override { cairo_restore(cr_); }
  Pt measure(const TextStyle& st, const std::string& s) override { return metrics_.measure(st, s); }

 private:
  void set(Colour c) { cairo_set_source_rgba(cr_, c.r / 255.0, c.g / 255.0, c.b / 255.0, c.a / 255.0); }
  void stroke(Colour c, double w) {
    set(c);
    cairo_set_line_width(cr_, w);
    cairo_stroke(cr_);
  }
  cairo_t* cr_;
  const FontMetrics& metrics_;
  bool raster_;
};

cairo_status_t append(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

void check(cairo_status_t st, const char* what) {
  if (st != CAIRO_STATUS_SUCCESS) throw std::runtime_error(std::string(what) + ": " + cairo_status_to_string(st));
}

}  // namespace

std::string render_figure_file(const DisplayList& fig, const FontMetrics& metrics, FigureFormat format, double dpi,
                               const std::string& title) {
  if (fig.width_pt <= 0 || fig.height_pt <= 0) throw std::runtime_error("figure has no size");
  std::string bytes;
  if (format == FigureFormat::kSvg) return render_svg(fig, metrics);
  if (format == FigureFormat::kPdf) {
    cairo_surface_t* surface = cairo_pdf_surface_create_for_stream(append, &bytes, fig.width_pt, fig.height_pt);
    cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_CREATOR, "ipd figure (IPD Studio)");
    if (!title.empty()) cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_TITLE, title.c_str());
    if (!fig.description.empty())
      cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_SUBJECT, fig.description.c_str());
    cairo_t* cr = cairo_create(surface);
    CairoCanvas canvas(cr, metrics, false);
    fig.replay(canvas);
    cairo_show_page(cr);
    const cairo_status_t st = cairo_status(cr);
    cairo_destroy(cr);
    cairo_surface_finish(surface);
    cairo_surface_destroy(surface);
    check(st, "PDF drawing");
    return bytes;
  }
  const double scale = dpi / 72.0;
  const int w = static_cast<int>(std::lround(fig.width_pt * scale)),
            h = static_cast<int>(std::ceil(fig.height_pt * scale));
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h);
  check(cairo_surface_status(surface), "PNG surface");
  cairo_t* cr = cairo_create(surface);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_scale(cr, scale, scale);
  CairoCanvas canvas(cr, metrics, true);
  fig.replay(canvas);
  const cairo_status_t st = cairo_status(cr);
  cairo_destroy(cr);
  if (st == CAIRO_STATUS_SUCCESS) cairo_surface_write_to_png_stream(surface, append, &bytes);
  cairo_surface_destroy(surface);
  check(st, "PNG drawing");
  return fig.description.empty() ? bytes : png_with_text(bytes, "Description", fig.description);
}

}  // namespace ipd::ui
