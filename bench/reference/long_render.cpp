#include "long_render.h"

#include "giq/base/error.h"
#include "giq/image/io.h"

namespace giq::bench {

namespace {

void finish(LongRender& r) {
  r.variance_term = 0.0;
  for (size_t k = 0; k < r.mean.size(); ++k)
    r.variance_term += r.variance[k] / (r.mean[k] * r.mean[k] + 0.01);
  r.variance_term /= double(r.mean.size());
}

}  // namespace

LongRender LongRender::from_film(const reference::Film& film) {
  LongRender r;
  r.width = film.width;
  r.height = film.height;
  r.spp = double(film.min_samples());
  r.mean.resize(film.pixels.size() * 3);
  r.variance.resize(film.pixels.size() * 3);
  for (size_t i = 0; i < film.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      r.mean[3 * i + size_t(c)] = film.pixels[i].mean[c];
      r.variance[3 * i + size_t(c)] = film.pixels[i].variance_of_mean(c);
    }
  finish(r);
  return r;
}

LongRender LongRender::from_exr(const std::filesystem::path& path) {
  const image::Image img = image::read_image(path);
  LongRender r;
  r.width = img.width();
  r.height = img.height();
  r.mean.resize(img.pixel_count() * 3);
  r.variance.resize(img.pixel_count() * 3);
  const char* mean_names[3] = {"R", "G", "B"};
  const char* var_names[3] = {"variance.R", "variance.G", "variance.B"};
  for (int c = 0; c < 3; ++c) {
    if (!img.has_channel(var_names[c]))
      throw InputError(path.string(), var_names[c],
                       "a long render needs the variance layer of `giq reference`");
    const float* m = img.channel(mean_names[c]);
    const float* v = img.channel(var_names[c]);
    for (size_t i = 0; i < img.pixel_count(); ++i) {
      r.mean[3 * i + size_t(c)] = double(m[i]);
      r.variance[3 * i + size_t(c)] = double(v[i]);
    }
  }
  const float* spp = img.has_channel("spp") ? img.channel("spp") : nullptr;
  r.spp = spp ? double(spp[0]) : 0.0;
  if (const auto it = img.metadata.find("giq.scene_hash"); it != img.metadata.end())
    r.scene_hash = it->second;
  if (const auto it = img.metadata.find("giq.view"); it != img.metadata.end()) r.view = it->second;
  if (const auto it = img.metadata.find("giq.settings"); it != img.metadata.end())
    r.settings = it->second;
  finish(r);
  return r;
}

double LongRender::rel_mse(const image::Image& image, const std::filesystem::path& file) const {
  if (image.width() != width || image.height() != height)
    throw InputError(file.string(), "size",
                     std::to_string(image.width()) + "x" + std::to_string(image.height()) +
                         ", expected " + std::to_string(width) + "x" + std::to_string(height) +
                         " like the long render");
  const float* ch[3] = {image.channel("R"), image.channel("G"), image.channel("B")};
  return rel_mse_of([&](size_t i, int c) { return ch[c][i]; });
}

}  // namespace giq::bench
