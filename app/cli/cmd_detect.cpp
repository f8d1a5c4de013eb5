// `ipd detect IMAGES_DIR --onnx MODEL.onnx --out PRED_DIR` and `ipd detect STUDY --onnx MODEL --model NAME`:
// a YOLOv5 ONNX export (or the demo's classical detector) run on pictures, written as YOLO txt predictions.
#include <fmt/format.h>

#include <filesystem>
#include <future>
#include <set>

#include "app/cli/cli_common.h"
#include "app/cli/commands.h"
#include "core/detect/rock_detector.h"
#include "core/detect/yolo.h"
#include "core/io/label_io.h"
#include "core/picture/picture_codec.h"
#include "core/study/file_sets.h"
#include "core/study/study.h"
#include "core/study/study_names.h"
#include "core/util/contained_file.h"

namespace fs = std::filesystem;

namespace ipd::cli {

namespace {

// One picture to detect on and where its predictions go: `out` in pictures mode; in study mode `relative`
// below the study `root`, written without following a link (a study is untrusted: `real/predictions ->
// /elsewhere` must not make the tool write there).
struct Job {
  std::string picture, out, root, relative;
};

std::vector<Job> jobs_for_dir(const fs::path& images, const fs::path& out) {
  static const std::set<std::string> kExt = {".png", ".jpg", ".jpeg", ".tif", ".tiff", ".bmp", ".webp"};
  std::vector<Job> jobs;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(images, ec)) {
    std::string ext = e.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    if (!kExt.count(ext)) continue;
    // A picture that is not a regular file (a FIFO, a link out of a study) gets no predictions: its scene would
    // later read as "nothing detected", so it is an error, not a skip.
    if (const std::string why = study_file_problem(e.path().string()); !why.empty()) throw StudyError(why);
    jobs.push_back({e.path().string(), (out / (e.path().stem().string() + ".txt")).string(), {}, {}});
  }
  if (ec) throw StudyError(images.string() + ": cannot read the directory: " + ec.message());
  std::sort(jobs.begin(), jobs.end(), [](const Job& a, const Job& b) { return a.picture < b.picture; });
  return jobs;
}

struct Args {
  std::string input, onnx, out, model, detector = "yolo";
  YoloOptions yolo;
  int threads = 0;
  bool replace = false;
};

// A folder the predictions go to, as write_file_beneath / remove_file_beneath take it.
struct Target {
  std::string root, relative;
  std::string dir() const { return relative.empty() ? root : (fs::path(root) / relative).string(); }
};

// Refused before the first file is written: a folder that already holds label files takes this run's only with
// --replace, as two runs' files would otherwise mix (the old run's file of a picture this run did not see stays).
void check_targets(const std::vector<Target>& targets, bool replace) {
  if (replace) return;
  std::string held;
  for (const Target& t : targets) {
    const std::vector<std::string> files = label_files_in(t.dir());
    if (files.empty()) continue;
    held += fmt::format("{}{}: already holds {} label file{} (e.g. {})", held.empty() ? "" : "\n", t.dir(),
                        files.size(), files.size() == 1 ? "" : "s", files.front());
  }
  if (!held.empty())
    throw StudyError(held +
                     "\nthe predictions of two runs would mix, so nothing is written (--replace replaces the whole "
                     "set: the .txt files this run does not write are removed)");
}

void check_args(const Args& args) {
  if (args.threads < 0)
    throw CLI::ValidationError("--threads", fmt::format("must be >= 0 (0: every core), got {}", args.threads));
  if (const std::string bad = args.yolo.validate(); !bad.empty()) throw CLI::ValidationError(bad);
  if (args.model.empty() == args.out.empty())
    throw CLI::ValidationError("detect",
                               "give --out PRED_DIR for a directory of pictures, or --model NAME for a study");
  if (!args.model.empty())
    if (const std::string why = file_name_problem(args.model, kMaxModelNameBytes); !why.empty())
      throw CLI::ValidationError("--model", fmt::format("'{}' {}", args.model, why));
  if (args.detector == "yolo" && args.onnx.empty())
    throw CLI::ValidationError("detect", "--onnx MODEL.onnx is required (or --detector classical)");
}

// The pictures to detect on, and the folders this run fills (PRED_DIR, or every domain's predictions/NAME, with
// pictures or not: a replaced set is the model's predictions in the whole study).
std::vector<Job> collect_jobs(const Args& args, std::vector<Target>* targets) {
  std::vector<Job> jobs;
  if (args.model.empty()) {
    // A domain's labels/ (beside its images/, or in a folder with study.yaml) is ground truth: detections written
    // there would become it, --replace or not. A study's predictions go to <domain>/predictions/NAME.
    fs::path out = fs::absolute(args.out).lexically_normal();
    if (out.filename().empty()) out = out.parent_path();
    std::error_code ec;
    if (out.filename() == "labels" && (fs::is_directory(out.parent_path() / "images", ec) ||
                                       fs::exists(out.parent_path().parent_path() / "study.yaml", ec)))
      throw StudyError(args.out +
                       ": is a domain's ground-truth labels; detections written there would replace them, so nothing "
                       "is written (a study's predictions: ipd detect STUDY --model NAME)");
    targets->push_back({args.out, ""});
    if (!fs::is_directory(args.input)) throw StudyError(args.input + ": no such directory of pictures");
    jobs = jobs_for_dir(args.input, args.out);
    if (jobs.empty()) throw StudyError(args.input + ": no pictures (png, jpg, tif, bmp, webp) in this directory");
    return jobs;
  }
  const Study st = open_study(args.input);
  for (const auto& d : st.domains) {
    const fs::path relative = fs::path(d.name) / "predictions" / args.model;
    targets->push_back({st.root, relative.string()});
    for (Job j : jobs_for_dir(fs::path(d.dir) / "images", fs::path(d.dir) / "predictions" / args.model)) {
      j.root = st.root;
      j.relative = (relative / fs::path(j.out).filename()).string();
      jobs.push_back(std::move(j));
    }
  }
  if (jobs.empty()) throw StudyError(args.input + ": no pictures in any <domain>/images/ directory");
  // Refused before the first file is written: a study is filled for every domain or not at all.
  for (const Job& j : jobs) check_beneath(j.root, j.relative);
  return jobs;
}

// Runs the detector on every job, decoding the next batch in parallel while it works; the number of
// pictures that could not be decoded.
int detect_all(const std::vector<Job>& jobs, YoloDetector* yolo, int threads, std::set<std::string>* written) {
  Progress progress("detecting");
  int failed = 0;
  auto decode = [](const std::string& p) { return read_picture(p, cv::IMREAD_COLOR); };
  std::vector<std::future<cv::Mat>> batch;
  size_t next = 0;
  auto fill = [&] {
    batch.clear();
    for (int k = 0; k < threads && next + k < jobs.size(); ++k)
      batch.push_back(std::async(std::launch::async, decode, jobs[next + k].picture));
  };
  fill();
  while (next < jobs.size()) {
    std::vector<cv::Mat> pictures;
    for (auto& f : batch) pictures.push_back(f.get());
    const size_t start = next;
    next += pictures.size();
    fill();
    for (size_t k = 0; k < pictures.size(); ++k) {
      const Job& job = jobs[start + k];
      if (pictures[k].empty()) {
        fmt::print(stderr, "{}: cannot decode the picture; skipped\n", job.picture);
        ++failed;
        continue;
      }
      const std::vector<Box> boxes = yolo ? yolo->detect(pictures[k]) : detect_rocks(pictures[k], RockDetectorParams{});
      if (job.root.empty())
        write_labels(job.out, boxes, LabelKind::kPrediction);
      else
        write_file_beneath(job.root, job.relative, labels_text(boxes, LabelKind::kPrediction));
      written->insert(job.root.empty() ? fs::path(job.out).filename().string() : job.relative);
      progress.update(static_cast<int>(start + k + 1), static_cast<int>(jobs.size()));
    }
  }
  return failed;
}

}  // namespace

Runner add_detect_command(CLI::App& app) {
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("detect", "Run a YOLOv5 ONNX export (or the classical detector) on pictures");
  cmd->add_option("INPUT", args->input, "A directory of pictures, or a study (with --model)")->required();
  cmd->add_option("--onnx", args->onnx, "YOLOv5 ONNX export (export.py --include onnx)");
  cmd->add_option("--out", args->out, "Directory for the predictions (pictures mode)");
  cmd->add_option("--model", args->model, "Study mode: fill STUDY/<domain>/predictions/NAME/ for every domain");
  cmd->add_option("--detector", args->detector, "yolo (default) or classical (the demo's OpenCV detector)")
      ->check(CLI::IsMember({"yolo", "classical"}));
  cmd->add_option("--imgsz", args->yolo.imgsz, "Network input size (square)");
  cmd->add_option("--conf", args->yolo.conf, "Confidence threshold");
  cmd->add_option("--iou", args->yolo.iou, "NMS IoU threshold");
  cmd->add_option("--classes", args->yolo.classes, "Keep only these classes, e.g. 0,1")->delimiter(',');
  cmd->add_option("--threads", args->threads, "Picture decoding threads (default: all cores)");
  cmd->add_flag(
      "--replace", args->replace,
      "Replace the label files a prediction folder already holds (those this run does not write are removed)");
  return [args]() -> int {
    check_args(*args);
    std::vector<Target> targets;
    const std::vector<Job> jobs = collect_jobs(*args, &targets);
    check_targets(targets, args->replace);
    std::unique_ptr<YoloDetector> yolo;
    if (args->detector == "yolo") {
      yolo = std::make_unique<YoloDetector>(args->onnx, args->yolo);  // loaded once, layout checked
      fmt::print(stderr, "{}: {} head, {} classes\n", args->onnx, yolo->head() == YoloHead::kV5 ? "YOLOv5" : "YOLOv8",
                 yolo->classes());
    }
    const int threads =
        std::max(1, args->threads > 0 ? args->threads : static_cast<int>(std::thread::hardware_concurrency()));
    std::set<std::string> written;
    const int failed = detect_all(jobs, yolo.get(), threads, &written);
    int removed = 0;
    if (args->replace)
      for (const Target& t : targets) {
        std::set<std::string> keep;
        for (const std::string& w : written)  // a file name in pictures mode, a path below the study in study mode
          if (fs::path(w).parent_path() == fs::path(t.relative)) keep.insert(fs::path(w).filename().string());
        removed += remove_files_not_kept(t.root, t.relative, keep, ".txt");
      }
    if (removed > 0) fmt::print("{} label file{} of the earlier run removed\n", removed, removed == 1 ? "" : "s");
    fmt::print("{} pictures, predictions written{}\n", jobs.size() - failed,
               failed ? fmt::format(", {} could not be decoded", failed) : "");
    return failed ? kBadInput : kOk;
  };
}

}  // namespace ipd::cli
