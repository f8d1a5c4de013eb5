// A study is untrusted input: none of its files or folders that is a symbolic link is read (a prediction file
// linked elsewhere changed the IPD without a word), and a picture that is a FIFO can't block a reader.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <functional>

#include "core/ipd/ipd.h"
#include "core/picture/picture_codec.h"
#include "core/picture/picture_size.h"
#include "core/study/study.h"
#include "core/util/contained_file.h"
#include "tests/support/test_support.h"

namespace fs = std::filesystem;

namespace ipd {
namespace {

std::string refused_study_links(const std::string& path) {
  return path + ": is a symbolic link; reading through it is refused (links inside a study are never followed)";
}

// Each way a study can hold a link, and what it points at: a copy outside the study with other boxes.
TEST(StudyLinks, EveryLinkedFileOrFolderIsRefusedWhenTheStudyIsRead) {
  struct Case {
    const char* inside;  // replaced by a link to a copy of itself outside
    bool folder;
  };
  for (const Case& c : {Case{"synth/predictions/det/s1.txt", false}, Case{"synth/predictions/det", true},
                        Case{"synth/predictions", true}, Case{"real/labels/s1.txt", false}, Case{"real/labels", true},
                        Case{"synth", true}, Case{"study.yaml", false}}) {
    test::TempDir d, elsewhere;
    test::write_two_rock_study(d);
    test::write_text(d / "study.yaml", "domains: [real, synth]\n");
    const std::string inside = d / c.inside, outside = elsewhere / "target";
    fs::rename(inside, outside);
    if (c.folder)
      fs::create_directory_symlink(outside, inside);
    else
      fs::create_symlink(outside, inside);
    EXPECT_EQ(test::open_study_error(d.path()), refused_study_links(inside)) << c.inside;
  }
}

// A picture linked out of the study is refused as the study is read; read_picture never follows one either.
TEST(StudyLinks, ALinkedPictureIsRefused) {
  test::TempDir d, elsewhere;
  test::write_two_rock_study(d);
  fs::create_directories(d / "real/images");
  test::write_text(elsewhere / "s1.png", "not a picture");
  fs::create_symlink(elsewhere / "s1.png", d / "real/images/s1.png");
  EXPECT_EQ(test::open_study_error(d.path()), refused_study_links(d / "real/images/s1.png"));
  EXPECT_EQ(study_file_problem(d / "real/images/s1.png"), refused_study_links(d / "real/images/s1.png"));
  EXPECT_TRUE(read_picture(d / "real/images/s1.png", cv::IMREAD_COLOR).empty());
}

// A FIFO named like a picture: every reader says so at once instead of waiting forever in open().
TEST(StudyLinks, APictureThatIsAFifoNeverBlocks) {
  test::TempDir d;
  const std::string fifo = d / "s1.png";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(study_file_problem(fifo), fifo + ": is a FIFO, expected a regular file");
  EXPECT_TRUE(read_picture(fifo, cv::IMREAD_COLOR).empty());
  EXPECT_EQ(study_file_problem(d / "none.png"), "");  // missing is the caller's to say
}

// A picture over the limit (here 8,000 x 7,000 = 56 megapixels; a 60 KB PNG can declare 400) is refused
// before its pixels are allocated, as a picture that can't be decoded: the image metrics need ~100 bytes a pixel.
TEST(StudyLinks, APictureOfTooManyPixelsIsRefusedBeforeDecoding) {
  test::TempDir d;
  std::vector<uchar> png;
  ASSERT_TRUE(encode_picture(".png", cv::Mat(7000, 8000, CV_8UC1, cv::Scalar(0)), &png));
  test::write_text(d / "big.png", std::string(png.begin(), png.end()));
  EXPECT_LT(png.size(), 200000u);
  EXPECT_EQ(picture_size_problem(d / "big.png"),
            d / "big.png" + ": declares 8000 x 7000 pixels, over the 50-megapixel limit for a picture");
  EXPECT_TRUE(read_picture(d / "big.png", cv::IMREAD_GRAYSCALE).empty());
  // JPEG (its size after the EXIF segment) and BMP headers.
  std::vector<uchar> jpeg, bmp;
  ASSERT_TRUE(encode_picture(".jpg", cv::Mat(30, 50, CV_8UC3, cv::Scalar(1, 2, 3)), &jpeg));
  test::write_text(d / "a.jpg", std::string(jpeg.begin(), jpeg.end()));
  ASSERT_TRUE(declared_picture_size(d / "a.jpg"));
  EXPECT_EQ(declared_picture_size(d / "a.jpg")->width, 50);
  EXPECT_EQ(declared_picture_size(d / "a.jpg")->height, 30);
  ASSERT_TRUE(encode_picture(".bmp", cv::Mat(30, 50, CV_8UC3, cv::Scalar(1, 2, 3)), &bmp));
  test::write_text(d / "a.bmp", std::string(bmp.begin(), bmp.end()));
  EXPECT_EQ(declared_picture_size(d / "a.bmp")->width, 50);
  EXPECT_EQ(declared_picture_size(d / "a.bmp")->height, 30);
  // A picture within the limit still reads.
  std::vector<uchar> small;
  ASSERT_TRUE(encode_picture(".png", cv::Mat(4, 6, CV_8UC1, cv::Scalar(7)), &small));
  test::write_text(d / "small.png", std::string(small.begin(), small.end()));
  EXPECT_EQ(read_picture(d / "small.png", cv::IMREAD_GRAYSCALE).cols, 6);
}

// Swapped for a link after the study was scanned, a label file is still not read through it.
TEST(StudyLinks, ALabelFileSwappedForALinkAfterTheScanIsNotFollowed) {
  test::TempDir d, elsewhere;
  test::write_two_rock_study(d);
  const Study s = open_study(d.path());
  test::write_text(elsewhere / "s1.txt", "0 0.5 0.5 0.1 0.1 0.99\n");
  const std::string file = d / "synth/predictions/det/s1.txt";
  fs::remove(file);
  fs::create_symlink(elsewhere / "s1.txt", file);
  const StudyLabels labels = load_labels(s);
  ASSERT_EQ(labels.errors.size(), 1u);
  EXPECT_EQ(labels.errors[0].to_string(), refused_study_links(file));
  EXPECT_TRUE(labels.predictions.at("synth").at("det").at("s1").boxes.empty());
}

}  // namespace
}  // namespace ipd
