#include "tests/support/pdf_text.h"

#include <gtest/gtest.h>

#include <regex>

#include "tests/support/test_support.h"

namespace ipd::test {

std::string PdfText::all() const {
  std::string s;
  for (const Word& w : words) s += w.text + " ";
  return s;
}

PdfText pdf_text(const std::string& pdf) {
  const auto r = run_command("pdftotext -bbox '" + pdf + "' -");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  PdfText t;
  std::smatch m;
  if (std::regex_search(r.out, m, std::regex(R"re(<page width="([\d.]+)" height="([\d.]+)">)re")))
    t.width = std::stod(m[1]), t.height = std::stod(m[2]);
  const std::regex word(R"re(<word xMin="([\d.]+)" yMin="([\d.]+)" xMax="([\d.]+)" yMax="([\d.]+)">([^<]*)</word>)re");
  for (auto it = std::sregex_iterator(r.out.begin(), r.out.end(), word); it != std::sregex_iterator(); ++it)
    t.words.push_back({std::stod((*it)[1]), std::stod((*it)[2]), std::stod((*it)[3]), std::stod((*it)[4]), (*it)[5]});
  return t;
}

std::string pdf_words(const std::string& pdf) {
  const auto r = run_command("pdftotext -raw '" + pdf + "' -");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return std::regex_replace(r.out, std::regex("\\s+"), " ");
}

bool has_word(const PdfText& t, const std::string& w) {
  for (const Word& x : t.words)
    if (x.text == w) return true;
  return false;
}

std::vector<std::string> overlapping(const PdfText& t) {
  std::vector<std::string> out;
  const double e = 0.05;
  for (size_t i = 0; i < t.words.size(); ++i)
    for (size_t j = 0; j < i; ++j) {
      const Word &a = t.words[i], &b = t.words[j];
      if (a.x0 + e < b.x1 && b.x0 + e < a.x1 && a.y0 + e < b.y1 && b.y0 + e < a.y1)
        out.push_back(a.text + " / " + b.text);
    }
  return out;
}

}  // namespace ipd::test
