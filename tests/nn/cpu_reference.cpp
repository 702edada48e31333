#include "nn/cpu_reference.h"

#include <algorithm>
#include <cmath>

namespace sixway::test {

CpuMap concat(const CpuMap& a, const CpuMap& b) {
  CpuMap out(a.channels + b.channels, a.height, a.width);
  std::copy(a.values.begin(), a.values.end(), out.values.begin());
  std::copy(b.values.begin(), b.values.end(), out.values.begin() + a.values.size());
  return out;
}

CpuMap conv2d(const CpuMap& in, const std::vector<float>& weight, const std::vector<float>& bias,
              int outChannels, int kernel, int stride) {
  const int pad = kernel / 2;
  const int height = (in.height + 2 * pad - kernel) / stride + 1,
            width = (in.width + 2 * pad - kernel) / stride + 1;
  CpuMap out(outChannels, height, width);
  for (int o = 0; o < outChannels; ++o)
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        double sum = bias[o];
        for (int i = 0; i < in.channels; ++i)
          for (int ky = 0; ky < kernel; ++ky)
            for (int kx = 0; kx < kernel; ++kx) {
              const int sy = y * stride + ky - pad, sx = x * stride + kx - pad;
              if (sy < 0 || sx < 0 || sy >= in.height || sx >= in.width) continue;
              sum += double(weight[((size_t(o) * in.channels + i) * kernel + ky) * kernel + kx]) *
                     in.at(i, sy, sx);
            }
        out.at(o, y, x) = float(sum);
      }
  return out;
}

CpuMap depthwise3x3(const CpuMap& in, const std::vector<float>& weight, const std::vector<float>& bias) {
  CpuMap out(in.channels, in.height, in.width);
  for (int c = 0; c < in.channels; ++c)
    for (int y = 0; y < in.height; ++y)
      for (int x = 0; x < in.width; ++x) {
        double sum = bias[c];
        for (int ky = 0; ky < 3; ++ky)
          for (int kx = 0; kx < 3; ++kx) {
            const int sy = y + ky - 1, sx = x + kx - 1;
            if (sy >= 0 && sx >= 0 && sy < in.height && sx < in.width)
              sum += double(weight[c * 9 + ky * 3 + kx]) * in.at(c, sy, sx);
          }
        out.at(c, y, x) = float(sum);
      }
  return out;
}

CpuMap convTranspose2x2(const CpuMap& in, const std::vector<float>& weight, const std::vector<float>& bias,
                        int outChannels) {
  CpuMap out(outChannels, in.height * 2, in.width * 2);
  for (int o = 0; o < outChannels; ++o)
    for (int y = 0; y < out.height; ++y)
      for (int x = 0; x < out.width; ++x) {
        double sum = bias[o];
        for (int i = 0; i < in.channels; ++i)
          sum += double(weight[((size_t(i) * outChannels + o) * 2 + y % 2) * 2 + x % 2]) *
                 in.at(i, y / 2, x / 2);
        out.at(o, y, x) = float(sum);
      }
  return out;
}

CpuMap activate(CpuMap map, nn::Activation activation, float negativeSlope) {
  for (float& v : map.values) {
    const double x = v;
    switch (activation) {
      case nn::Activation::None:
        break;
      case nn::Activation::Relu:
        v = float(std::max(x, 0.0));
        break;
      case nn::Activation::LeakyRelu:
        v = float(x >= 0 ? x : x * negativeSlope);
        break;
      case nn::Activation::Gelu:
        v = float(0.5 * x * (1.0 + std::erf(x / std::sqrt(2.0))));
        break;
      case nn::Activation::Silu:
        v = float(x / (1.0 + std::exp(-x)));
        break;
    }
  }
  return map;
}

CpuMap upsampleBilinear(const CpuMap& in, int factor) {
  CpuMap out(in.channels, in.height * factor, in.width * factor);
  auto source = [factor](int dst, int size, int& lower, int& upper, double& lambda) {
    const double s = std::max((dst + 0.5) / factor - 0.5, 0.0);
    lower = int(s);
    upper = std::min(lower + 1, size - 1);
    lambda = s - lower;
  };
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      int y0, y1, x0, x1;
      double ly, lx;
      source(y, in.height, y0, y1, ly);
      source(x, in.width, x0, x1, lx);
      for (int c = 0; c < in.channels; ++c)
        out.at(c, y, x) = float((1 - ly) * ((1 - lx) * in.at(c, y0, x0) + lx * in.at(c, y0, x1)) +
                                ly * ((1 - lx) * in.at(c, y1, x0) + lx * in.at(c, y1, x1)));
    }
  return out;
}

CpuMap layerNorm2d(const CpuMap& in, const std::vector<float>& weight, const std::vector<float>& bias,
                   float eps) {
  CpuMap out(in.channels, in.height, in.width);
  for (int y = 0; y < in.height; ++y)
    for (int x = 0; x < in.width; ++x) {
      double mean = 0, variance = 0;
      for (int c = 0; c < in.channels; ++c) mean += in.at(c, y, x);
      mean /= in.channels;
      for (int c = 0; c < in.channels; ++c) variance += (in.at(c, y, x) - mean) * (in.at(c, y, x) - mean);
      variance /= in.channels;
      for (int c = 0; c < in.channels; ++c)
        out.at(c, y, x) = float(weight[c] * (in.at(c, y, x) - mean) / std::sqrt(variance + eps) + bias[c]);
    }
  return out;
}

CpuMap simpleGate(const CpuMap& in) {
  const int half = in.channels / 2;
  CpuMap out(half, in.height, in.width);
  for (int c = 0; c < half; ++c)
    for (int y = 0; y < in.height; ++y)
      for (int x = 0; x < in.width; ++x) out.at(c, y, x) = in.at(c, y, x) * in.at(c + half, y, x);
  return out;
}

CpuMap nafBlock(const CpuMap& in, const nn::ParameterMap& p, float eps) {
  auto get = [&p](const char* key) -> const std::vector<float>& { return p.at(key); };
  const int dw = int(get("conv1.bias").size()), ffn = int(get("conv4.bias").size());
  CpuMap x = layerNorm2d(in, get("norm1.weight"), get("norm1.bias"), eps);
  x = conv2d(x, get("conv1.weight"), get("conv1.bias"), dw, 1, 1);
  x = simpleGate(depthwise3x3(x, get("conv2.weight"), get("conv2.bias")));
  // Simplified channel attention: the global average of each channel through a 1x1 conv scales the channel.
  CpuMap mean(x.channels, 1, 1);
  for (int c = 0; c < x.channels; ++c) {
    double sum = 0;
    for (int i = 0; i < x.height * x.width; ++i) sum += x.values[size_t(c) * x.height * x.width + i];
    mean.at(c, 0, 0) = float(sum / (x.height * x.width));
  }
  const CpuMap scale = conv2d(mean, get("sca.weight"), get("sca.bias"), x.channels, 1, 1);
  for (int c = 0; c < x.channels; ++c)
    for (int i = 0; i < x.height * x.width; ++i)
      x.values[size_t(c) * x.height * x.width + i] *= scale.at(c, 0, 0);
  x = conv2d(x, get("conv3.weight"), get("conv3.bias"), in.channels, 1, 1);
  CpuMap y = in;
  const size_t plane = size_t(in.height) * in.width;
  for (size_t i = 0; i < y.values.size(); ++i) y.values[i] += x.values[i] * get("beta")[i / plane];
  x = layerNorm2d(y, get("norm2.weight"), get("norm2.bias"), eps);
  x = simpleGate(conv2d(x, get("conv4.weight"), get("conv4.bias"), ffn, 1, 1));
  x = conv2d(x, get("conv5.weight"), get("conv5.bias"), in.channels, 1, 1);
  for (size_t i = 0; i < y.values.size(); ++i) y.values[i] += x.values[i] * get("gamma")[i / plane];
  return y;
}

float srgbToLinear(float v) {
  return v <= 0.04045f ? v / 12.92f : float(std::pow((v + 0.055) / 1.055, 2.4));
}

}  // namespace sixway::test
