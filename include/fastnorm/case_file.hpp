#pragma once
/// @file case_file.hpp
/// Reader and writer of the `.case` text format (docs/case-format.md): one normal
/// contact problem, optionally with a steady-rolling problem on it and a solution.

#include <Eigen/Core>
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <istream>
#include <limits>
#include <map>
#include <optional>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "fastnorm/detail/memory_check.hpp"
#include "fastnorm/error.hpp"
#include "fastnorm/grid.hpp"
#include "fastnorm/material.hpp"
#include "fastnorm/solution.hpp"
#include "fastnorm/tangential_problem.hpp"

namespace fastnorm {

/// A `.case` file that does not follow the format; `line()` is 1-based (0: no line).
class case_format_error : public invalid_argument {
 public:
  /// `what` may be another fastnorm error's message: its "fastnorm: " is not repeated.
  case_format_error(const std::string& source, int line, const std::string& what)
      : invalid_argument("fastnorm: " + source + (line > 0 ? ":" + std::to_string(line) : "") + ": " +
                         (what.rfind("fastnorm: ", 0) == 0 ? what.substr(10) : what)),
        line_(line) {}
  int line() const { return line_; }

 private:
  int line_;
};

/// The optional solution part of a case.
template <typename Scalar = double>
struct CaseResult {
  Scalar normal_force = 0;  ///< N
  Scalar approach = 0;      ///< m
  Eigen::Index contact_count = 0;
  int iterations = 0;
  Scalar solve_seconds = 0;  ///< s
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> pressure;  ///< Pa, grid.size() values
};

/// The optional steady-rolling problem of a case (its `tangential` line): Coulomb friction
/// and the creepages of body 1 against body 2 (docs/tangential.md §5).
template <typename Scalar = double>
struct CaseRolling {
  Scalar friction = 0;  ///< μ
  Creepage<Scalar> creepage;
  RollingDirection direction = RollingDirection::positive_x;
};

/// One normal-contact problem as stored in a `.case` file.
template <typename Scalar = double>
struct Case {
  std::string name;
  std::string source;
  Grid<Scalar> grid;
  /// One material for both bodies (the format stores a single E and ν).
  Material<Scalar> material;
  Loading<Scalar> loading;
  /// The value on a `control approach` line (m): informational, h already contains it.
  Scalar stated_approach = 0;
  /// h on every element (m, + = gap).
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> undeformed_distance;
  std::optional<CaseResult<Scalar>> result;
  std::optional<CaseRolling<Scalar>> rolling;  ///< a steady-rolling problem on the normal one
};

namespace detail {

/// Line-by-line tokenizer for `.case` text: strips comments, skips blank lines.
class CaseLines {
 public:
  CaseLines(std::istream& in, std::string source) : in_(in), source_(std::move(source)) {}

  /// Next non-blank line split into words; false at the end of input.
  bool next(std::vector<std::string>& words, std::string& text) {
    std::string line;
    while (std::getline(in_, line)) {
      ++number_;
      const auto hash = line.find('#');
      if (hash != std::string::npos) line.erase(hash);
      std::istringstream split(line);
      words.clear();
      for (std::string word; split >> word;) words.push_back(word);
      if (!words.empty()) {
        text = line;
        return true;
      }
    }
    return false;
  }
  int number() const { return number_; }
  [[noreturn]] void fail(const std::string& what) const { throw case_format_error(source_, number_, what); }

 private:
  std::istream& in_;
  std::string source_;
  int number_ = 0;
};

/// A decimal number as the format writes it: [+-] digits [. digits] [e [+-] digits], with
/// digits on at least one side of the point; no hexadecimal, inf or nan (strtold's extras).
inline bool is_decimal(const std::string& word) {
  std::size_t k = 0;
  auto digits = [&] {
    const std::size_t start = k;
    while (k < word.size() && std::isdigit(static_cast<unsigned char>(word[k]))) ++k;
    return k - start;
  };
  if (k < word.size() && (word[k] == '+' || word[k] == '-')) ++k;
  std::size_t mantissa = digits();
  if (k < word.size() && word[k] == '.') {
    ++k;
    mantissa += digits();
  }
  if (mantissa == 0) return false;
  if (k < word.size() && (word[k] == 'e' || word[k] == 'E')) {
    ++k;
    if (k < word.size() && (word[k] == '+' || word[k] == '-')) ++k;
    if (digits() == 0) return false;
  }
  return k == word.size();
}

template <typename Scalar>
Scalar parse_number(const CaseLines& lines, const std::string& word, const std::string& what) {
  if (!is_decimal(word)) lines.fail("malformed number '" + word + "' for " + what + " (decimal numbers only)");
  const long double value = std::strtold(word.c_str(), nullptr);
  const auto scalar = static_cast<Scalar>(value);
  if (!std::isfinite(value) || !std::isfinite(scalar)) {
    lines.fail("number '" + word + "' for " + what + " is out of range");
  }
  return scalar;
}

inline long parse_integer(const CaseLines& lines, const std::string& word, const std::string& what) {
  const char* begin = word.c_str();
  char* end = nullptr;
  errno = 0;
  const long value = std::strtol(begin, &end, 10);
  if (end == begin || *end != '\0') lines.fail("malformed integer '" + word + "' for " + what);
  if (errno == ERANGE) lines.fail("integer '" + word + "' for " + what + " is out of range");
  return value;
}

/// A line that starts with a word (not a number, nan or inf) ends a block of numbers.
inline bool is_keyword(const std::string& word) {
  if (!std::isalpha(static_cast<unsigned char>(word[0]))) return false;
  std::string lower;
  for (char c : word) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return lower != "nan" && lower != "inf" && lower != "infinity";
}

/// Reads `keyword v1 key2 v2 …` with the keys in the given order; returns the values.
inline std::vector<std::string> keyed_values(const CaseLines& lines,
                                             const std::vector<std::string>& words,
                                             const std::vector<std::string>& keys) {
  if (words.size() != 1 + 2 * keys.size()) {
    lines.fail("'" + words[0] + "' line needs " + std::to_string(keys.size()) + " key/value pairs");
  }
  std::vector<std::string> values;
  for (std::size_t n = 0; n < keys.size(); ++n) {
    if (words[1 + 2 * n] != keys[n]) {
      lines.fail("'" + words[0] + "' line: expected key '" + keys[n] + "', found '" +
                 words[1 + 2 * n] + "'");
    }
    values.push_back(words[2 + 2 * n]);
  }
  return values;
}

/// Rest of the line after its first word (for name and source).
inline std::string rest_of_line(const std::string& text, const std::string& keyword) {
  const auto start = text.find(keyword) + keyword.size();
  const auto first = text.find_first_not_of(" \t", start);
  if (first == std::string::npos) return {};
  const auto last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

/// The sections of a `.case` file in their order (docs/case-format.md), one step each;
/// every fault names its line.
template <typename Scalar>
class CaseReader {
 public:
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;

  CaseReader(std::istream& in, const std::string& source_name) : lines_(in, source_name), source_name_(source_name) {}

  Case<Scalar> read() {
    if (!lines_.next(words_, text_) || words_.size() != 2 || words_[0] != "fastnorm-case" || words_[1] != "1") {
      throw case_format_error(source_name_, lines_.number(), "first line must be 'fastnorm-case 1'");
    }
    expect("name");
    const std::string name = rest_of_line(text_, "name");
    expect("source");
    const std::string source = rest_of_line(text_, "source");
    const Grid<Scalar> grid = read_grid();
    const Material<Scalar> material = read_material();
    Case<Scalar> problem{name,      source,   grid,         material,    Loading<Scalar>::approach(),
                         Scalar(0), Vector(), std::nullopt, std::nullopt};
    read_control(problem);
    if (!lines_.next(words_, text_)) throw case_format_error(source_name_, lines_.number(), "missing 'h' line");
    if (words_[0] == "tangential") {
      problem.rolling = read_rolling();
      expect("h");
    } else if (words_[0] != "h") {
      lines_.fail("expected 'tangential' or 'h', found '" + words_[0] + "'");
    }
    bool more = false;
    problem.undeformed_distance = read_block("h", grid.size(), more);
    if (more) problem.result = read_result(grid.size());
    return problem;
  }

 private:
  void expect(const std::string& keyword) {
    if (!lines_.next(words_, text_)) {
      throw case_format_error(source_name_, lines_.number(), "missing '" + keyword + "' line");
    }
    if (words_[0] != keyword) lines_.fail("expected '" + keyword + "', found '" + words_[0] + "'");
  }

  Scalar number(const std::string& word, const std::string& what) const {
    return parse_number<Scalar>(lines_, word, what);
  }

  Grid<Scalar> read_grid() {
    expect("grid");
    const auto g = keyed_values(lines_, words_, {"mx", "my", "dx", "dy", "x0", "y0"});
    const long mx = parse_integer(lines_, g[0], "mx");
    const long my = parse_integer(lines_, g[1], "my");
    const Scalar dx = number(g[2], "dx");
    const Scalar dy = number(g[3], "dy");
    if (mx < 1 || my < 1 || !(dx > 0) || !(dy > 0)) lines_.fail("grid sizes must be positive (mx, my >= 1; dx, dy > 0)");
    try {  // h alone, before its block is read
      detail::check_memory(static_cast<double>(mx) * static_cast<double>(my), sizeof(Scalar), "grid mx x my");
    } catch (const invalid_argument& error) {
      lines_.fail(error.what());
    }
    return Grid<Scalar>(mx, my, dx, dy, number(g[4], "x0"), number(g[5], "y0"));
  }

  Material<Scalar> read_material() {
    expect("material");
    const auto m = keyed_values(lines_, words_, {"E", "nu"});
    const Scalar young = number(m[0], "E");
    const Scalar poisson = number(m[1], "nu");
    try {
      return Material<Scalar>(young, poisson);
    } catch (const invalid_argument& error) {
      lines_.fail(error.what());
    }
  }

  // `control force <N>` or `control approach <m>` (the approach is informational).
  void read_control(Case<Scalar>& problem) {
    expect("control");
    if (words_.size() != 3 || (words_[1] != "force" && words_[1] != "approach")) {
      lines_.fail("control line must be 'control force <N>' or 'control approach <m>'");
    }
    const Scalar value = number(words_[2], "control");
    if (words_[1] == "force") {
      if (!(value > 0)) lines_.fail("control force must be positive (N)");
      problem.loading = Loading<Scalar>::force(value);
    } else {
      problem.stated_approach = value;
    }
  }

  // `tangential friction <μ> xi <ξ> eta <η> phi <rad/m> xc <m> yc <m> rolling +x|-x`.
  CaseRolling<Scalar> read_rolling() {
    const auto t = keyed_values(lines_, words_, {"friction", "xi", "eta", "phi", "xc", "yc", "rolling"});
    CaseRolling<Scalar> rolling;
    rolling.friction = number(t[0], "friction");
    if (!(rolling.friction > 0)) lines_.fail("tangential friction must be positive");
    rolling.creepage.longitudinal = number(t[1], "xi");
    rolling.creepage.lateral = number(t[2], "eta");
    rolling.creepage.spin = number(t[3], "phi");
    rolling.creepage.spin_centre_x = number(t[4], "xc");
    rolling.creepage.spin_centre_y = number(t[5], "yc");
    if (t[6] != "+x" && t[6] != "-x") lines_.fail("tangential rolling must be +x or -x, found '" + t[6] + "'");
    rolling.direction = t[6] == "+x" ? RollingDirection::positive_x : RollingDirection::negative_x;
    return rolling;
  }

  // A block of `count` numbers after its keyword line; `more` tells whether a keyword line
  // (now in words_) ended it rather than the end of the file. The storage grows with the
  // numbers read, so a short file that states a huge grid fails at its end without first
  // allocating mx*my values.
  Vector read_block(const std::string& keyword, Eigen::Index count, bool& more) {
    std::vector<Scalar> values;
    values.reserve(static_cast<std::size_t>(std::min<Eigen::Index>(count, 1 << 16)));
    more = false;
    while (lines_.next(words_, text_)) {
      if (is_keyword(words_[0])) {
        more = true;
        break;
      }
      for (const auto& word : words_) {
        if (static_cast<Eigen::Index>(values.size()) == count) {
          lines_.fail("block '" + keyword + "' has more than mx*my = " + std::to_string(count) + " numbers");
        }
        values.push_back(number(word, "block '" + keyword + "'"));
      }
    }
    if (static_cast<Eigen::Index>(values.size()) != count) {
      lines_.fail("block '" + keyword + "' ends " + (more ? "here" : "at the end of the file") + " with " +
                  std::to_string(values.size()) + " numbers, expected mx*my = " + std::to_string(count));
    }
    return Eigen::Map<const Vector>(values.data(), count);
  }

  // The `result` line (already in words_) and the `p` block.
  CaseResult<Scalar> read_result(Eigen::Index count) {
    if (words_[0] != "result") lines_.fail("expected 'result' or end of file, found '" + words_[0] + "'");
    if (words_.size() % 2 != 1) lines_.fail("'result' line needs key/value pairs");
    std::map<std::string, std::string> fields;
    for (std::size_t n = 1; n + 1 < words_.size(); n += 2) fields[words_[n]] = words_[n + 1];
    for (const char* key : {"fn", "approach", "ncontact", "iterations", "solve_s"}) {
      if (!fields.count(key)) lines_.fail(std::string("'result' line lacks field '") + key + "'");
    }
    CaseResult<Scalar> stored;
    stored.normal_force = number(fields["fn"], "fn");
    stored.approach = number(fields["approach"], "approach");
    stored.contact_count = parse_integer(lines_, fields["ncontact"], "ncontact");
    stored.iterations = static_cast<int>(parse_integer(lines_, fields["iterations"], "iterations"));
    stored.solve_seconds = number(fields["solve_s"], "solve_s");
    expect("p");
    bool more = false;
    stored.pressure = read_block("p", count, more);
    if (more) lines_.fail("unexpected '" + words_[0] + "' after the 'p' block");
    return stored;
  }

  CaseLines lines_;
  std::string source_name_;
  std::vector<std::string> words_;  // the current line, split
  std::string text_;                // the current line, as written
};

}  // namespace detail

/// Reads a case from a stream.
/// @param source_name used in error messages (a file name)
/// @throws fastnorm::case_format_error with the line number for malformed input
template <typename Scalar = double>
Case<Scalar> read_case(std::istream& in, const std::string& source_name) {
  return detail::CaseReader<Scalar>(in, source_name).read();
}

/// Reads a case file.
/// @throws fastnorm::invalid_argument if the file cannot be opened, case_format_error
///         (with the line number) if it is malformed
template <typename Scalar = double>
Case<Scalar> read_case_file(const std::string& path) {
  std::ifstream in(path);
  FASTNORM_CHECK(in.good(), "cannot open case file '" + path + "'");
  return read_case<Scalar>(in, path);
}

/// Whether a case of `material` can be written: the format stores one E and ν.
/// @throws fastnorm::invalid_argument naming `material` when its two bodies differ
template <typename Scalar>
void check_case_material(const Material<Scalar>& material) {
  FASTNORM_CHECK(material.young_modulus(1) == material.young_modulus(2) &&
                     material.poisson_ratio(1) == material.poisson_ratio(2),
                 "material: a .case file holds one material, body 2 must equal body 1");
}

/// Writes a case (and its result, if any) in the `.case` format, full precision.
/// @throws fastnorm::invalid_argument for a material whose two bodies differ (check_case_material)
template <typename Scalar>
void write_case(std::ostream& out, const Case<Scalar>& problem) {
  check_case_material(problem.material);
  const auto& grid = problem.grid;
  out << std::setprecision(std::numeric_limits<Scalar>::max_digits10);
  auto block = [&](const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& values) {
    for (Eigen::Index j = 0; j < grid.my(); ++j) {
      for (Eigen::Index i = 0; i < grid.mx(); ++i) {
        out << (i ? " " : "") << values(grid.index(i, j));
      }
      out << '\n';
    }
  };
  out << "fastnorm-case 1\n"
      << "name " << problem.name << '\n'
      << "source " << problem.source << '\n'
      << "grid mx " << grid.mx() << " my " << grid.my() << " dx " << grid.dx() << " dy "
      << grid.dy() << " x0 " << grid.x0() << " y0 " << grid.y0() << '\n'
      << "material E " << problem.material.young_modulus() << " nu "
      << problem.material.poisson_ratio() << '\n';
  if (problem.loading.control == Control::force) {
    out << "control force " << problem.loading.normal_force << '\n';
  } else {
    out << "control approach " << problem.stated_approach << '\n';
  }
  if (problem.rolling) {
    const auto& rolling = *problem.rolling;
    out << "tangential friction " << rolling.friction << " xi " << rolling.creepage.longitudinal << " eta "
        << rolling.creepage.lateral << " phi " << rolling.creepage.spin << " xc " << rolling.creepage.spin_centre_x
        << " yc " << rolling.creepage.spin_centre_y << " rolling "
        << (rolling.direction == RollingDirection::positive_x ? "+x" : "-x") << '\n';
  }
  out << "h\n";
  block(problem.undeformed_distance);
  if (problem.result) {
    const auto& r = *problem.result;
    out << "result fn " << r.normal_force << " approach " << r.approach << " ncontact "
        << r.contact_count << " iterations " << r.iterations << " solve_s " << r.solve_seconds
        << "\np\n";
    block(r.pressure);
  }
}

/// Writes a case file (write_case into the file at `path`).
/// @throws fastnorm::invalid_argument if the bodies' materials differ (the format holds
///         one), or the file cannot be opened or written
template <typename Scalar>
void write_case_file(const std::string& path, const Case<Scalar>& problem) {
  check_case_material(problem.material);
  std::ofstream out(path);
  FASTNORM_CHECK(out.good(), "path: cannot open '" + path + "' for writing");
  write_case(out, problem);
  FASTNORM_CHECK(out.good(), "path: writing '" + path + "' failed");
}

}  // namespace fastnorm
