#include "ui/canvas/canvas_svg.h"

#include <fmt/format.h>

#include <set>
#include <stdexcept>

#include "core/picture/picture_codec.h"
#include "ui/canvas/font_subset.h"

namespace ipd::ui {

namespace {

std::string base64(const std::string& in) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((in.size() + 2) / 3 * 4);
  size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    const unsigned v = (unsigned char)in[i] << 16 | (unsigned char)in[i + 1] << 8 | (unsigned char)in[i + 2];
    out += {k[v >> 18], k[(v >> 12) & 63], k[(v >> 6) & 63], k[v & 63]};
  }
  if (i + 1 == in.size()) {
    const unsigned v = (unsigned char)in[i] << 16;
    out += {k[v >> 18], k[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == in.size()) {
    const unsigned v = (unsigned char)in[i] << 16 | (unsigned char)in[i + 1] << 8;
    out += {k[v >> 18], k[(v >> 12) & 63], k[(v >> 6) & 63], '='};
  }
  return out;
}

std::string xml_escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    switch (c) {
      case '&':
        o += "&amp;";
        break;
      case '<':
        o += "&lt;";
        break;
      case '>':
        o += "&gt;";
        break;
      case '"':
        o += "&quot;";
        break;
      default:
        o += c;
    }
  }
  return o;
}

std::string colour(Colour c) { return fmt::format("#{:02x}{:02x}{:02x}", c.r, c.g, c.b); }
std::string opacity(const char* attr, Colour c) {
  return c.a == 255 ? std::string() : fmt::format(" {}=\"{:.3f}\"", attr, c.a / 255.0);
}

class SvgCanvas : public Canvas {
 public:
  SvgCanvas(const FontMetrics& m) : metrics_(m) {}
  void rect(const PtRect& r, Colour c, double w) override {
    body_ += fmt::format("<rect x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" height=\"{:.2f}\" fill=\"none\"{}/>\n", r.x0,
                         r.y0, r.width(), r.height(), stroke(c, w));
  }
  void fill_rect(const PtRect& r, Colour c) override {
    body_ += fmt::format("<rect x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" height=\"{:.2f}\" fill=\"{}\"{}/>\n", r.x0,
                         r.y0, r.width(), r.height(), colour(c), opacity("fill-opacity", c));
  }
  void line(Pt a, Pt b, Colour c, double w) override {
    body_ += fmt::format("<line x1=\"{:.2f}\" y1=\"{:.2f}\" x2=\"{:.2f}\" y2=\"{:.2f}\"{}/>\n", a.x, a.y, b.x, b.y,
                         stroke(c, w));
  }
  void polyline(const std::vector<Pt>& pts, Colour c, double w, bool closed) override {
    std::string p;
    for (const Pt& q : pts) p += fmt::format("{:.2f},{:.2f} ", q.x, q.y);
    body_ += fmt::format("<{} points=\"{}\" fill=\"none\"{}/>\n", closed ? "polygon" : "polyline", p, stroke(c, w));
  }
  void circle(Pt c, double r, Colour col, double w) override {
    body_ += fmt::format("<circle cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"{:.2f}\" fill=\"none\"{}/>\n", c.x, c.y, r,
                         stroke(col, w));
  }
  void fill_circle(Pt c, double r, Colour col) override {
    body_ += fmt::format("<circle cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"{:.2f}\" fill=\"{}\"{}/>\n", c.x, c.y, r, colour(col),
                         opacity("fill-opacity", col));
  }
  void text(Pt at, Anchor anchor, const TextStyle& st, const std::string& s) override {
    const Pt m = metrics_.measure(st, s);
    const PtRect box = text_box(at, anchor, m.x, m.y);
    add_code_points(s, st.bold ? &bold_chars_ : &regular_chars_);
    body_ += fmt::format("<text x=\"{:.2f}\" y=\"{:.2f}\" font-size=\"{:.2f}\"{} fill=\"{}\"{}>{}</text>\n", box.x0,
                         box.y0 + metrics_.ascent(st), st.size_pt, st.bold ? " font-weight=\"bold\"" : "",
                         colour(st.colour), opacity("fill-opacity", st.colour), xml_escape(s));
  }
  void image(const FigurePicture& p, const PtRect& where) override {
    if (p.pixels.empty()) return;
    // Photographs: JPEG at quality 90 is a tenth of a lossless PNG and looks the same at print size. The
    // pixels are the crop's own (native resolution, never resampled).
    std::vector<uchar> jpeg;
    encode_picture(".jpg", p.pixels, &jpeg, {cv::IMWRITE_JPEG_QUALITY, 90});
    body_ += fmt::format(
        "<image x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" height=\"{:.2f}\" preserveAspectRatio=\"none\" "
        "xlink:href=\"data:image/jpeg;base64,{}\"/>\n",
        where.x0, where.y0, where.width(), where.height(), base64(std::string(jpeg.begin(), jpeg.end())));
  }
  void push_clip(const PtRect& r) override {
    const int id = clips_++;
    body_ += fmt::format(
        "<clipPath id=\"clip{}\"><rect x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" height=\"{:.2f}\"/></clipPath>\n"
        "<g clip-path=\"url(#clip{})\">\n",
        id, r.x0, r.y0, r.width(), r.height(), id);
  }
  void pop_clip() override { body_ += "</g>\n"; }
  Pt measure(const TextStyle& st, const std::string& s) override { return metrics_.measure(st, s); }

  std::string body_;
  std::set<char32_t> regular_chars_, bold_chars_;  // the glyphs each weight needs

 private:
  std::string stroke(Colour c, double w) const {
    return fmt::format(" stroke=\"{}\" stroke-width=\"{:.2f}\"{}", colour(c), w, opacity("stroke-opacity", c));
  }
  const FontMetrics& metrics_;
  int clips_ = 0;
};

}  // namespace

std::string render_svg(const DisplayList& fig, const FontMetrics& metrics) {
  SvgCanvas svg(metrics);
  fig.replay(svg);
  // The font travels with the file, so the text looks the same wherever it is opened; only the glyphs the
  // figure uses (a few kB, not the whole face).
  std::string style;
  auto face = [&](const std::string& file, const std::set<char32_t>& chars, const char* weight) {
    style += "@font-face { font-family: 'IpdFigure'; src: url(data:font/ttf;base64," +
             base64(subset_font(file, chars)) + ") format('truetype'); font-weight: " + weight + "; }\n";
  };
  if (!svg.regular_chars_.empty()) face(metrics.file(), svg.regular_chars_, "normal");
  if (!svg.bold_chars_.empty())
    face(metrics.bold_file().empty() ? metrics.file() : metrics.bold_file(), svg.bold_chars_, "bold");
  return fmt::format(
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\" "
      "width=\"{0:.2f}pt\" height=\"{1:.2f}pt\" viewBox=\"0 0 {0:.2f} {1:.2f}\" font-family=\"IpdFigure, 'DejaVu "
      "Sans', "
      "sans-serif\">\n<style>\n{2}</style>\n<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n{3}</svg>\n",
      fig.width_pt, fig.height_pt, style, svg.body_);
}

}  // namespace ipd::ui
