#include "common/message.h"

#include <cstdio>
#include <stdexcept>

namespace hdrf {
namespace {

// A wording cut into its fixed text and its arguments: text[0] %a[0] text[1] %a[1] ... text[n].
struct Pieces {
  std::vector<std::string_view> text;
  std::vector<int> arg;  // 0-based argument numbers
};

Pieces Cut(std::string_view w) {
  Pieces p;
  std::size_t start = 0;
  for (std::size_t i = 0; i + 1 < w.size(); ++i)
    if (w[i] == '%' && w[i + 1] >= '1' && w[i + 1] <= '9') {
      p.text.push_back(w.substr(start, i - start));
      p.arg.push_back(w[i + 1] - '1');
      start = i + 2;
      ++i;
    }
  p.text.push_back(w.substr(start));
  return p;
}

// Matches text[k..] of `p` against s[at..], each argument the shortest non-empty run that lets
// the rest match. `budget` bounds the work (backtracking over a hostile text, a file name full
// of the wording's own fixed pieces, could otherwise take long): out of budget, no match.
bool Match(const Pieces& p, std::size_t k, std::string_view s, std::size_t at, std::vector<std::string_view>& got,
           long& budget) {
  const std::string_view fixed = p.text[k];
  if (s.substr(at, fixed.size()) != fixed) return false;
  at += fixed.size();
  if (k == p.arg.size()) return at == s.size();
  for (std::size_t end = at + 1; end <= s.size(); ++end) {
    if (--budget < 0) return false;
    got[k] = s.substr(at, end - at);
    if (Match(p, k + 1, s, end, got, budget)) return true;
  }
  return false;
}

}  // namespace

const std::vector<const Wording*>& AllWordings() {
  static const std::vector<const Wording*> all = {
#define HDRF_LIST_WORDING(id, text) &words::id,
      HDRF_WORDINGS(HDRF_LIST_WORDING)
#undef HDRF_LIST_WORDING
  };
  return all;
}

std::string Say(const Wording& w, std::initializer_list<std::string> args) {
  const Pieces p = Cut(w.english);
  if (p.arg.size() != args.size())
    throw std::logic_error(std::string("message ") + w.name + " takes " + std::to_string(p.arg.size()) +
                           " arguments, given " + std::to_string(args.size()));
  std::string out(p.text[0]);
  for (std::size_t k = 0; k < p.arg.size(); ++k) {
    if (std::size_t(p.arg[k]) >= args.size())
      throw std::logic_error(std::string("message ") + w.name + " names an argument it is not given");
    out += *(args.begin() + p.arg[k]);
    out += p.text[k + 1];
  }
  return out;
}

std::string Num(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

std::string Sig(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

std::optional<ParsedMessage> ParseMessage(std::string_view text) {
  std::optional<ParsedMessage> best;
  std::size_t best_fixed = 0;
  for (const Wording* w : AllWordings()) {
    const Pieces p = Cut(w->english);
    std::size_t fixed = 0;
    for (std::string_view t : p.text) fixed += t.size();
    if (best && fixed <= best_fixed) continue;
    const std::string_view last = p.text.back();
    if (text.size() < last.size() || text.substr(text.size() - last.size()) != last) continue;
    std::vector<std::string_view> got(p.arg.size());
    long budget = 20000;
    if (!Match(p, 0, text, 0, got, budget)) continue;
    ParsedMessage m;
    m.wording = w;
    m.args.resize(p.arg.size());
    for (std::size_t k = 0; k < p.arg.size(); ++k) m.args[std::size_t(p.arg[k])] = std::string(got[k]);
    best = std::move(m);
    best_fixed = fixed;
  }
  return best;
}

}  // namespace hdrf
