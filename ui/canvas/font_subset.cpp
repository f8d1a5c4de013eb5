#include "ui/canvas/font_subset.h"

#include <hb-subset.h>
#include <hb.h>

#include <memory>
#include <stdexcept>

namespace ipd::ui {

void add_code_points(const std::string& s, std::set<char32_t>* out) {
  for (size_t i = 0; i < s.size();) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    const int n = c < 0x80 ? 1 : (c >> 5) == 6 ? 2 : (c >> 4) == 14 ? 3 : (c >> 3) == 30 ? 4 : 0;
    if (n == 0 || i + n > s.size()) {
      out->insert(0xFFFD);
      ++i;
      continue;
    }
    char32_t cp = n == 1 ? c : c & (0x7F >> n);
    bool ok = true;
    for (int k = 1; k < n; ++k) {
      const unsigned char t = static_cast<unsigned char>(s[i + k]);
      ok &= (t >> 6) == 2;
      cp = (cp << 6) | (t & 0x3F);
    }
    out->insert(ok ? cp : 0xFFFD);
    i += ok ? n : 1;
  }
}

std::string subset_font(const std::string& file, const std::set<char32_t>& code_points) {
  // HarfBuzz objects, released whatever happens.
  std::unique_ptr<hb_blob_t, decltype(&hb_blob_destroy)> blob(hb_blob_create_from_file_or_fail(file.c_str()),
                                                              hb_blob_destroy);
  if (!blob) throw std::runtime_error(file + ": cannot read the font file");
  std::unique_ptr<hb_face_t, decltype(&hb_face_destroy)> face(hb_face_create(blob.get(), 0), hb_face_destroy);
  std::unique_ptr<hb_subset_input_t, decltype(&hb_subset_input_destroy)> input(hb_subset_input_create_or_fail(),
                                                                               hb_subset_input_destroy);
  if (!input) throw std::runtime_error(file + ": out of memory subsetting the font");
  hb_set_t* unicodes = hb_subset_input_unicode_set(input.get());
  for (char32_t cp : code_points) hb_set_add(unicodes, cp);
  // Hinting only helps tiny sizes on screen rasterisers that ignore it anyway; it is most of a glyph's bytes.
  hb_subset_input_set_flags(input.get(), HB_SUBSET_FLAGS_NO_HINTING);
  std::unique_ptr<hb_face_t, decltype(&hb_face_destroy)> sub(hb_subset_or_fail(face.get(), input.get()),
                                                             hb_face_destroy);
  if (!sub) throw std::runtime_error(file + ": the font could not be subset (not a TrueType/OpenType font?)");
  std::unique_ptr<hb_blob_t, decltype(&hb_blob_destroy)> out(hb_face_reference_blob(sub.get()), hb_blob_destroy);
  unsigned length = 0;
  const char* data = hb_blob_get_data(out.get(), &length);
  if (!data || length == 0) throw std::runtime_error(file + ": the font subset is empty");
  return std::string(data, length);
}

}  // namespace ipd::ui
