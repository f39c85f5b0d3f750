// `giq report` end to end: a folder of score outputs (one image comparison, one sequence) and a
// gate.json, with hostile names from files; the page escapes them, embeds every image, and
// headless Chromium renders it with the images visible where they are placed.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "support/subprocess.h"
#include "giq/image/image.h"
#include "giq/image/io.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

using giq::test::slurp;

void solid_exr(const fs::path& p, float r, float g, float b, const std::string& technique = "") {
  giq::image::Image img(24, 24);
  img.add_channel("R", r), img.add_channel("G", g), img.add_channel("B", b);
  if (!technique.empty()) img.metadata["giq.technique"] = technique;
  giq::image::write_exr(img, p);
}

// Debian's headless browser, or "" where it is not installed.
std::string chromium_binary() {
  for (const char* c : {"/usr/bin/chromium", "/usr/bin/chromium-browser"})
    if (fs::exists(c)) return c;
  return "";
}

const char* kHostileScene = "<script>alert(1)</script>.gltf";
const char* kHostileTechnique = "<img src=x onerror=alert(2)>";

class Report : public testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        fs::temp_directory_path() / ("giq_report_test_" + std::to_string(::getpid()) + "_" +
                                     testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    const fs::path a = dir_ / "cases" / "cornell-direct" / "score";
    fs::create_directories(a);
    // Reference pure red, technique pure blue, error map pure yellow: easy to find on screen.
    solid_exr(a / "ref.exr", 1, 0, 0);
    solid_exr(a / "tech.exr", 0, 0, 1, kHostileTechnique);
    const unsigned char yellow[3] = {255, 255, 0};
    std::vector<unsigned char> px;
    for (int i = 0; i < 24 * 24; ++i) px.insert(px.end(), yellow, yellow + 3);
    giq::image::write_png_rgb8(a / "abs_error.png", 24, 24, 3, px.data());
    json m = {{"inputs",
               {{"reference", "ref.exr"},
                {"test", "tech.exr"},
                {"layer", "beauty"},
                {"scene", kHostileScene}}},
              {"metrics", {{"relmse", {{"value", 0.25}}}, {"flip", {{"mean", {{"value", 0.1}}}}}}},
              {"warnings", {"the test's mean luminance is <2> times the reference's"}},
              {"maps",
               {{"abs_error",
                 {{"png", "abs_error.png"},
                  {"colormap", "magma"},
                  {"range", {0, 2}},
                  {"unit", "radiance"},
                  {"definition", "|T - R|"},
                  {"range_rule", "p99"}}}}}};
    std::ofstream(a / "metrics.json") << m.dump();

    const fs::path s = dir_ / "seq";
    fs::create_directories(s);
    for (int f = 0; f < 3; ++f) {
      char name[32];
      std::snprintf(name, sizeof name, "r_%04d.exr", f);
      solid_exr(s / name, 0.5f, 0.5f, 0.5f);
      std::snprintf(name, sizeof name, "t_%04d.exr", f);
      solid_exr(s / name, f * 0.3f, f * 0.3f, f * 0.3f, "pt");
    }
    json q = {{"inputs",
               {{"reference", "r_%04d.exr"},
                {"test", "t_%04d.exr"},
                {"frames", {0, 2}},
                {"layer", "beauty"},
                {"scene", "movinglight.gltf"}}},
              {"sequence", {{"flicker", {{"value", 0.3}}}}},
              {"last_frame", {{"metrics", {{"relmse", {{"value", 0.01}, {"unresolved", true}}}}}}}};
    std::ofstream(s / "metrics.json") << q.dump();
    json g = {{"passed", false},
              {"config", "gate.json"},
              {"outcomes",
               {{{"case", "<b>bold</b>"},
                 {"metric", "relmse"},
                 {"status", "FAIL"},
                 {"value", 0.25},
                 {"bound", "<= 0.1"},
                 {"message", "too big & wrong"}}}}};
    std::ofstream(dir_ / "gate.json") << g.dump();
  }
  // GIQ_KEEP_TEST_OUTPUT=1 keeps the page and the screenshot for a look.
  void TearDown() override {
    if (!HasFailure() && !std::getenv("GIQ_KEEP_TEST_OUTPUT")) fs::remove_all(dir_);
  }

  int giq(const std::string& args) {
    const std::string cmd =
        std::string(GIQ_BINARY) + " " + args + " >" + (dir_ / "out.txt").string() + " 2>&1";
    return giq::test::exit_code(std::system(cmd.c_str()));
  }

  fs::path dir_;
};

TEST_F(Report, EscapesTextFromFilesAndEmbedsImages) {
  ASSERT_EQ(giq("report " + dir_.string()), 0) << slurp(dir_ / "out.txt");
  const std::string html = slurp(dir_ / "report.html");
  EXPECT_EQ(html.find("<script>alert"), std::string::npos);
  EXPECT_NE(html.find("&lt;script&gt;alert(1)&lt;/script&gt;.gltf"), std::string::npos);
  EXPECT_EQ(html.find("<img src=x"), std::string::npos);
  EXPECT_NE(html.find("&lt;img src=x onerror=alert(2)&gt;"), std::string::npos);
  EXPECT_EQ(html.find("<b>bold</b>"), std::string::npos);
  EXPECT_NE(html.find("too big &amp; wrong"), std::string::npos);
  // Self-contained: nothing fetched from elsewhere.
  EXPECT_EQ(html.find("http://"), std::string::npos);
  EXPECT_EQ(html.find("https://"), std::string::npos);
  EXPECT_EQ(html.find("src=\"file:"), std::string::npos);
  // Two panes, their A/B pair and a map for the image comparison; 2 panes, their A/B pair and
  // 3 + 3 flip-book frames for the sequence.
  size_t pngs = 0;
  for (size_t p = 0; (p = html.find("src=\"data:image/png;base64,", p)) != std::string::npos; ++p)
    ++pngs;
  EXPECT_EQ(pngs, 5u + 4u + 6u);
  // The summary: a row per comparison, each headline metric with its unit and direction; the
  // score's warnings, escaped, in its section and counted in the summary.
  EXPECT_NE(html.find("<h2>Summary</h2>"), std::string::npos);
  EXPECT_NE(html.find("relmse<br><span class=\"hint\">1, lower is better</span>"), std::string::npos);
  EXPECT_NE(html.find("flip_mean<br>"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"num UNRESOLVED\">0.01 (unresolved)</td>"), std::string::npos);
  EXPECT_NE(html.find("warning: the test&#39;s mean luminance is &lt;2&gt; times"), std::string::npos);
  EXPECT_NE(html.find("1 warning(s)"), std::string::npos);
  EXPECT_NE(html.find("class=\"flipbook\""), std::string::npos);
  EXPECT_NE(html.find("unresolved"), std::string::npos);
  EXPECT_EQ(giq("report " + (dir_ / "absent").string()), 2);
}

TEST_F(Report, ReadsNoFileOutsideItsFolderAndEmbedsOnlyImages) {
  // A metrics.json beside real images whose error map names a text file outside the report's
  // folder, absolutely or by "..", or a text file inside it: once embedded as base64.
  const fs::path secret = dir_ / "secret.txt", shared = dir_ / "shared";
  std::ofstream(secret) << "SECRET-CONTENT";
  const fs::path a = dir_ / "cases" / "cornell-direct" / "score";
  std::ofstream(a / "notes.png") << "SECRET-CONTENT";
  json m = json::parse(slurp(a / "metrics.json"));
  for (const std::string& png : {secret.string(), std::string("../../../secret.txt"), std::string("notes.png")}) {
    SCOPED_TRACE(png);
    fs::remove_all(shared);
    fs::create_directories(shared / "x" / "y");
    for (const char* f : {"ref.exr", "tech.exr"}) fs::copy_file(a / f, shared / "x" / "y" / f);
    m["maps"]["abs_error"]["png"] = png;
    if (png == "notes.png") fs::copy_file(a / "notes.png", shared / "x" / "y" / "notes.png");
    std::ofstream(shared / "x" / "y" / "metrics.json") << m.dump();
    EXPECT_EQ(giq("report " + shared.string()), 2) << slurp(dir_ / "out.txt");
    const std::string said = slurp(dir_ / "out.txt");
    EXPECT_TRUE(said.find("outside") != std::string::npos || said.find("not a PNG") != std::string::npos) << said;
    EXPECT_FALSE(fs::exists(shared / "report.html"));
  }
}

TEST_F(Report, AGateJsonThatIsNotTheGatesIsAnInputError) {
  // Once an internal error (exit 3): the page read it as the gate's object.
  const fs::path only = dir_ / "only";
  fs::create_directories(only);
  std::ofstream(only / "gate.json") << "[]";
  EXPECT_EQ(giq("report " + only.string()), 2) << slurp(dir_ / "out.txt");
  EXPECT_NE(slurp(dir_ / "out.txt").find("gate.json: outcomes: missing"), std::string::npos) << slurp(dir_ / "out.txt");
}

TEST_F(Report, ChromiumShowsTheImages) {
  const std::string chromium = chromium_binary();
  if (chromium.empty()) GTEST_SKIP() << "chromium is not installed (tools/bootstrap installs it)";
  ASSERT_EQ(giq("report " + dir_.string()), 0) << slurp(dir_ / "out.txt");
  const fs::path shot = dir_ / "shot.png", profile = dir_ / "profile";
  const std::string cmd =
      chromium +
      " --headless --no-sandbox --disable-gpu --disable-quic --no-first-run"
      " --disable-background-networking --disable-component-update --disable-sync"
      " --hide-scrollbars --user-data-dir=" +
      profile.string() + " --screenshot=" + shot.string() + " --window-size=1400,1400 file://" +
      (dir_ / "report.html").string() + " >" + (dir_ / "chromium.log").string() + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << slurp(dir_ / "chromium.log");
  ASSERT_TRUE(fs::exists(shot)) << slurp(dir_ / "chromium.log");
  const giq::image::Image img = giq::image::read_image(shot);
  ASSERT_EQ(img.width(), 1400);
  // Each 24 px image is shown in a 320 x 320 pane (object-fit: contain): 102400 pixels of its
  // colour when the pane is on screen. Half of that tolerates a pane partly below the fold.
  size_t red = 0, blue = 0, yellow = 0, other = 0;
  const float *r = img.channel("R"), *g = img.channel("G"), *b = img.channel("B");
  for (size_t i = 0; i < size_t(img.width()) * size_t(img.height()); ++i) {
    const bool R = r[i] > 0.95f, G = g[i] > 0.95f, B = b[i] > 0.95f;
    const bool r0 = r[i] < 0.05f, g0 = g[i] < 0.05f, b0 = b[i] < 0.05f;
    if (R && g0 && b0)
      ++red;
    else if (r0 && g0 && B)
      ++blue;
    else if (R && G && b0)
      ++yellow;
    else
      ++other;
  }
  EXPECT_GT(red, 51200u);
  EXPECT_GT(blue, 51200u);
  EXPECT_GT(yellow, 51200u);
  EXPECT_GT(other, 0u);  // not one flat colour: the page itself rendered too
}

}  // namespace

namespace {

// An image whose every pixel is known: R = x/8, G = y/8, B = `b` (technique: twice that).
void ramp_exr(const fs::path& p, float scale, const std::string& technique = "") {
  giq::image::Image img(16, 16);
  float *r = img.add_channel("R"), *g = img.add_channel("G"), *b = img.add_channel("B");
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const size_t i = img.index(x, y);
      r[i] = scale * float(x) / 8.0f, g[i] = scale * float(y) / 8.0f, b[i] = scale * 0.5f;
    }
  if (!technique.empty()) img.metadata["giq.technique"] = technique;
  giq::image::write_exr(img, p);
}

}  // namespace

// Pointing at a pixel of a comparison's image reads out that pixel's values from the EXRs: in
// headless Chromium, a pointer move over pixel (5, 7) of the reference pane, dispatched once
// the page has loaded, and the readout in the DOM afterwards.
TEST_F(Report, PointingAtAPixelReadsItsValues) {
  const std::string chromium = chromium_binary();
  if (chromium.empty()) GTEST_SKIP() << "chromium is not installed (tools/bootstrap installs it)";
  const fs::path d = dir_ / "readout";
  fs::create_directories(d);
  ramp_exr(d / "ref.exr", 1.0f);
  ramp_exr(d / "tech.exr", 2.0f, "ramp");
  giq::image::Image map(16, 16);
  float* v = map.add_channel("Y");
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) v[map.index(x, y)] = float(x + y) / 16.0f;
  giq::image::write_exr(map, d / "abs_error.exr");
  std::vector<unsigned char> px(16 * 16 * 3, 128);
  giq::image::write_png_rgb8(d / "abs_error.png", 16, 16, 3, px.data());
  const json m = {{"inputs", {{"reference", "ref.exr"}, {"test", "tech.exr"}, {"layer", "beauty"}}},
                  {"metrics", {{"relmse", {{"value", 0.5}}}}},
                  {"maps",
                   {{"abs_error",
                     {{"png", "abs_error.png"}, {"exr", "abs_error.exr"}, {"colormap", "magma"}, {"range", {0, 2}},
                      {"unit", "radiance"}, {"definition", "|T - R|"}, {"range_rule", "0 to the 99th percentile"}}}}}};
  std::ofstream(d / "metrics.json") << m.dump();
  ASSERT_EQ(giq("report " + d.string() + " --out " + (d / "report.html").string()), 0) << slurp(dir_ / "out.txt");
  // The page, with a script that points at the centre of pixel (5, 7) of the first pane: 16
  // pixels fill the 320-pixel pane, 20 screen pixels each.
  std::string page = slurp(d / "report.html");
  const std::string poke = R"(<script>window.addEventListener('load',function(){
  var v=document.querySelector('.comparison .row.sync .view'),r=v.querySelector('img').getBoundingClientRect();
  v.dispatchEvent(new PointerEvent('pointermove',{clientX:r.left+5.5*20*r.width/320,clientY:r.top+7.5*20*r.height/320,bubbles:true}));
  document.body.setAttribute('data-readout',document.querySelector('.readout').textContent);});</script></body>)";
  page.replace(page.rfind("</body>"), 7, poke);
  std::ofstream(d / "poked.html") << page;
  const std::string cmd = chromium +
                          " --headless --no-sandbox --disable-gpu --disable-quic --no-first-run"
                          " --disable-background-networking --disable-component-update --disable-sync --user-data-dir=" +
                          (dir_ / "profile").string() + " --window-size=1400,1400 --dump-dom file://" +
                          (d / "poked.html").string() + " >" + (d / "dom.html").string() + " 2>" +
                          (d / "chromium.log").string();
  ASSERT_EQ(std::system(cmd.c_str()), 0) << slurp(d / "chromium.log");
  const std::string dom = slurp(d / "dom.html");
  EXPECT_NE(dom.find("pixel (5, 7): reference (0.625, 0.875, 0.5) \u00b7 ramp (1.25, 1.75, 1) \u00b7 abs_error 0.75"),
            std::string::npos)
      << dom.substr(0, 400);
  // The colour bar's five ticks, the top one standing for everything above it.
  EXPECT_NE(page.find("<span>0</span><span>0.5</span><span>1</span><span>1.5</span><span>&ge;2</span>"), std::string::npos);
}
