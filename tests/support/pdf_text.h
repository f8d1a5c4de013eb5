// A PDF's text as poppler-utils reads it (pdftotext -bbox / -raw), for the figure tests.
#pragma once

#include <string>
#include <vector>

namespace ipd::test {

struct Word {
  double x0, y0, x1, y1;
  std::string text;
};
struct PdfText {
  double width = 0, height = 0;
  std::vector<Word> words;
  std::string all() const;  // the words joined by spaces
};

// pdftotext -bbox: the page size and every word's box (points, y down).
PdfText pdf_text(const std::string& pdf);
// pdftotext -raw with every run of white space one space.
std::string pdf_words(const std::string& pdf);
bool has_word(const PdfText& text, const std::string& word);
// Pairs of words whose boxes overlap by more than a hair (0.05 pt: poppler rounds), "A / B".
std::vector<std::string> overlapping(const PdfText& text);

}  // namespace ipd::test
