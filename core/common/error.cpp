#include "common/error.h"

#include "common/cuda_runtime.h"

namespace hdrf {

std::string Printable(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  const auto escape = [&](unsigned char b) {
    static constexpr char kHex[] = "0123456789abcdef";
    out += "\\x";
    out += kHex[b >> 4];
    out += kHex[b & 15];
  };
  const auto* s = reinterpret_cast<const unsigned char*>(text.data());
  const std::size_t n = text.size();
  for (std::size_t i = 0; i < n;) {
    const unsigned char b = s[i];
    if (b < 0x80) {
      if (b < 0x20 || b == 0x7f)
        escape(b);
      else
        out += char(b);
      ++i;
      continue;
    }
    // A UTF-8 sequence: its length from the lead byte, then continuation bytes, no overlong
    // forms, no surrogates, nothing above U+10FFFF.
    const std::size_t len = b >= 0xc2 && b <= 0xdf ? 2 : b >= 0xe0 && b <= 0xef ? 3 : b >= 0xf0 && b <= 0xf4 ? 4 : 0;
    bool ok = len > 0 && i + len <= n;
    char32_t cp = len == 2 ? b & 0x1f : len == 3 ? b & 0x0f : b & 0x07;
    for (std::size_t k = 1; ok && k < len; ++k) {
      ok = (s[i + k] & 0xc0) == 0x80;
      cp = (cp << 6) | (s[i + k] & 0x3f);
    }
    ok = ok && !(len == 3 && cp < 0x800) && !(len == 4 && (cp < 0x10000 || cp > 0x10ffff)) &&
         !(cp >= 0xd800 && cp <= 0xdfff);
    if (!ok) {
      escape(b);
      ++i;
    } else if (cp >= 0x80 && cp <= 0x9f) {  // C1 controls (CSI among them)
      for (std::size_t k = 0; k < len; ++k) escape(s[i + k]);
      i += len;
    } else {
      out.append(text.substr(i, len));
      i += len;
    }
  }
  return out;
}

std::string FormatInputMessage(const std::filesystem::path& file, int line,
                               const std::string& what) {
  std::string s = file.string();
  if (line > 0) {
    s += ':';
    s += std::to_string(line);
  }
  s += ": ";
  s += what;
  return s;
}

void ThrowNoCudaBackend() {
  throw Error("this build of HDRFusion has no CUDA backend (nvcc was not found when it was "
              "configured); use --device cpu, or rebuild on a machine with the CUDA toolkit");
}

}  // namespace hdrf
