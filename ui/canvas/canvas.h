// The drawing interface figures draw through once. Units are points (1/72 in), y down, origin top left.
// Backends: ImGui's draw list (canvas_imgui.h: the GUI, the OSMesa PNG path of `ipd figure`) and cairo
// (canvas_cairo.h: PDF, SVG, PNG without a GL context). A DisplayList records a drawing so its height can
// be known before a page of that height is made, and replays it into any backend.
#pragma once

#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace ipd::ui {

struct Colour {
  std::uint8_t r = 0, g = 0, b = 0, a = 255;
};
constexpr Colour rgb(int r, int g, int b, int a = 255) {
  return {std::uint8_t(r), std::uint8_t(g), std::uint8_t(b), std::uint8_t(a)};
}

struct Pt {
  double x = 0, y = 0;
};
struct PtRect {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  double width() const { return x1 - x0; }
  double height() const { return y1 - y0; }
};

// Where `at` sits on the text's box (advance width x line height: ascent + descent).
enum class Anchor { kTopLeft, kTop, kTopRight, kLeft, kCentre, kRight, kBottomLeft, kBottom, kBottomRight };

struct TextStyle {
  double size_pt = 8;
  Colour colour;
  bool bold = false;
};

// The box a text occupies when drawn at `at` with `anchor`, given its measured size.
PtRect text_box(Pt at, Anchor anchor, double width, double height);

// A picture (BGR, 8 bit) and where its pixels go; `pixels` is already cut to what is shown.
struct FigurePicture {
  cv::Mat pixels;
};

class Canvas {
 public:
  virtual ~Canvas() = default;
  virtual void rect(const PtRect& r, Colour stroke, double width_pt) = 0;
  virtual void fill_rect(const PtRect& r, Colour fill) = 0;
  virtual void line(Pt a, Pt b, Colour colour, double width_pt) = 0;
  virtual void polyline(const std::vector<Pt>& points, Colour colour, double width_pt, bool closed) = 0;
  virtual void circle(Pt centre, double radius_pt, Colour stroke, double width_pt) = 0;
  virtual void fill_circle(Pt centre, double radius_pt, Colour fill) = 0;
  virtual void text(Pt at, Anchor anchor, const TextStyle& style, const std::string& s) = 0;
  virtual void image(const FigurePicture& picture, const PtRect& where) = 0;
  virtual void push_clip(const PtRect& r) = 0;
  virtual void pop_clip() = 0;
  // Advance width and line height (ascent + descent) of `s` in points.
  virtual Pt measure(const TextStyle& style, const std::string& s) = 0;
};

// Measures text with a font file through FreeType (cairo-ft); the metrics every figure layout uses, so
// that PDF, SVG and PNG of one figure have the same layout.
class FontMetrics {
 public:
  explicit FontMetrics(const std::string& font_file);  // throws std::runtime_error when unreadable
  ~FontMetrics();
  FontMetrics(const FontMetrics&) = delete;
  FontMetrics& operator=(const FontMetrics&) = delete;
  Pt measure(const TextStyle& style, const std::string& s) const;
  double ascent(const TextStyle& style) const;  // baseline below the top of the line box
  // The font faces (regular, bold) as cairo_font_face_t*, for the cairo backend.
  void* regular_face() const;
  void* bold_face() const;
  const std::string& file() const { return file_; }
  const std::string& bold_file() const { return bold_file_; }  // empty: bold is synthesised

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string file_, bold_file_;
};

// "" when `font_file` is a regular file (whether it holds a font is FreeType's to say), else what is wrong,
// naming the file: "no such font file", or what is there instead ("is a character device, not a font file").
std::string font_file_problem(const std::string& font_file);

// The default figure font: DejaVu Sans from fonts-dejavu-core (or assets/fonts/ when present).
std::string default_font_file();

// Records drawing operations (measuring with FontMetrics) and replays them into another canvas.
class DisplayList : public Canvas {
 public:
  explicit DisplayList(const FontMetrics& metrics) : metrics_(metrics) {}
  void rect(const PtRect& r, Colour stroke, double width_pt) override;
  void fill_rect(const PtRect& r, Colour fill) override;
  void line(Pt a, Pt b, Colour colour, double width_pt) override;
  void polyline(const std::vector<Pt>& points, Colour colour, double width_pt, bool closed) override;
  void circle(Pt centre, double radius_pt, Colour stroke, double width_pt) override;
  void fill_circle(Pt centre, double radius_pt, Colour fill) override;
  void text(Pt at, Anchor anchor, const TextStyle& style, const std::string& s) override;
  void image(const FigurePicture& picture, const PtRect& where) override;
  void push_clip(const PtRect& r) override;
  void pop_clip() override;
  Pt measure(const TextStyle& style, const std::string& s) override { return metrics_.measure(style, s); }

  void replay(Canvas& out) const;
  const FontMetrics& metrics() const { return metrics_; }
  // Every text drawn, with its box (for tests and the overlap check).
  struct TextItem {
    PtRect box;
    std::string text;
    double size_pt;
  };
  std::vector<TextItem> texts() const;

  // Page size in points: set by the figure once its content is laid out.
  double width_pt = 0, height_pt = 0;
  // Written into the file, not drawn: the PDF's Subject, the SVG's <desc>, the PNG's "Description" text
  // chunk (where the figures record the label files and hand edits they were drawn from).
  std::string description;

 private:
  enum class Op { kRect, kFillRect, kLine, kPolyline, kCircle, kFillCircle, kText, kImage, kPushClip, kPopClip };
  struct Item {
    Op op = Op::kRect;
    std::vector<Pt> points;
    PtRect r;
    Colour colour;
    double width = 0;
    bool closed = false;
    Anchor anchor = Anchor::kTopLeft;
    TextStyle style;
    std::string s;
    FigurePicture picture;
  };
  const FontMetrics& metrics_;
  std::vector<Item> items_;
};

}  // namespace ipd::ui
