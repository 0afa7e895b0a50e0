#pragma once
/// @file case_file.hpp
/// Reader and writer of the `.case` text format (docs/case-format.md): one normal
/// contact problem, optionally with a solution.

#include <Eigen/Core>
#include <cctype>
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

#include "fastnorm/error.hpp"
#include "fastnorm/grid.hpp"
#include "fastnorm/material.hpp"
#include "fastnorm/solution.hpp"

namespace fastnorm {

/// A `.case` file that does not follow the format; `line()` is 1-based (0: no line).
class case_format_error : public invalid_argument {
 public:
  case_format_error(const std::string& source, int line, const std::string& what)
      : invalid_argument("fastnorm: " + source + (line > 0 ? ":" + std::to_string(line) : "") +
                         ": " + what),
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

template <typename Scalar>
Scalar parse_number(const CaseLines& lines, const std::string& word, const std::string& what) {
  const char* begin = word.c_str();
  char* end = nullptr;
  const long double value = std::strtold(begin, &end);
  if (end == begin || *end != '\0') lines.fail("malformed number '" + word + "' for " + what);
  if (!std::isfinite(value)) lines.fail("non-finite number '" + word + "' for " + what);
  return static_cast<Scalar>(value);
}

inline long parse_integer(const CaseLines& lines, const std::string& word, const std::string& what) {
  const char* begin = word.c_str();
  char* end = nullptr;
  const long value = std::strtol(begin, &end, 10);
  if (end == begin || *end != '\0') lines.fail("malformed integer '" + word + "' for " + what);
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

}  // namespace detail

/// Reads a case from a stream.
/// @param source_name used in error messages (a file name)
/// @throws fastnorm::case_format_error with the line number for malformed input
template <typename Scalar = double>
Case<Scalar> read_case(std::istream& in, const std::string& source_name) {
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  detail::CaseLines lines(in, source_name);
  std::vector<std::string> words;
  std::string text;

  auto expect = [&](const std::string& keyword) {
    if (!lines.next(words, text)) {
      throw case_format_error(source_name, lines.number(), "missing '" + keyword + "' line");
    }
    if (words[0] != keyword) {
      lines.fail("expected '" + keyword + "', found '" + words[0] + "'");
    }
  };
  // Reads a block of numbers after a keyword line; `after` receives the line that ended it.
  auto read_block = [&](const std::string& keyword, Eigen::Index count, bool& more) {
    Vector values(count);
    Eigen::Index filled = 0;
    more = false;
    while (lines.next(words, text)) {
      if (detail::is_keyword(words[0])) {
        more = true;
        break;
      }
      for (const auto& word : words) {
        if (filled == count) {
          lines.fail("block '" + keyword + "' has more than mx*my = " + std::to_string(count) +
                     " numbers");
        }
        values(filled++) = detail::parse_number<Scalar>(lines, word, "block '" + keyword + "'");
      }
    }
    if (filled != count) {
      lines.fail("block '" + keyword + "' ends " + (more ? "here" : "at the end of the file") +
                 " with " + std::to_string(filled) + " numbers, expected mx*my = " +
                 std::to_string(count));
    }
    return values;
  };

  if (!lines.next(words, text) || words.size() != 2 || words[0] != "fastnorm-case" ||
      words[1] != "1") {
    throw case_format_error(source_name, lines.number(), "first line must be 'fastnorm-case 1'");
  }
  expect("name");
  const std::string name = detail::rest_of_line(text, "name");
  expect("source");
  const std::string source = detail::rest_of_line(text, "source");

  expect("grid");
  const auto g = detail::keyed_values(lines, words, {"mx", "my", "dx", "dy", "x0", "y0"});
  const long mx = detail::parse_integer(lines, g[0], "mx");
  const long my = detail::parse_integer(lines, g[1], "my");
  const Scalar dx = detail::parse_number<Scalar>(lines, g[2], "dx");
  const Scalar dy = detail::parse_number<Scalar>(lines, g[3], "dy");
  if (mx < 1 || my < 1 || !(dx > 0) || !(dy > 0)) {
    lines.fail("grid sizes must be positive (mx, my >= 1; dx, dy > 0)");
  }
  const Grid<Scalar> grid(mx, my, dx, dy, detail::parse_number<Scalar>(lines, g[4], "x0"),
                          detail::parse_number<Scalar>(lines, g[5], "y0"));

  expect("material");
  const auto m = detail::keyed_values(lines, words, {"E", "nu"});
  const Scalar young = detail::parse_number<Scalar>(lines, m[0], "E");
  const Scalar poisson = detail::parse_number<Scalar>(lines, m[1], "nu");
  std::optional<Material<Scalar>> material;
  try {
    material.emplace(young, poisson);
  } catch (const invalid_argument& error) {
    lines.fail(error.what());
  }

  expect("control");
  if (words.size() != 3 || (words[1] != "force" && words[1] != "approach")) {
    lines.fail("control line must be 'control force <N>' or 'control approach <m>'");
  }
  const Scalar control_value = detail::parse_number<Scalar>(lines, words[2], "control");
  Loading<Scalar> loading = Loading<Scalar>::approach();
  if (words[1] == "force") {
    if (!(control_value > 0)) lines.fail("control force must be positive (N)");
    loading = Loading<Scalar>::force(control_value);
  }

  const Scalar stated_approach = words[1] == "approach" ? control_value : Scalar(0);

  expect("h");
  bool more = false;
  Case<Scalar> result_case{name,   source,          grid,     *material,
                           loading, stated_approach, Vector(), std::nullopt};
  result_case.undeformed_distance = read_block("h", grid.size(), more);
  if (!more) return result_case;

  if (words[0] != "result") lines.fail("expected 'result' or end of file, found '" + words[0] + "'");
  if (words.size() % 2 != 1) lines.fail("'result' line needs key/value pairs");
  std::map<std::string, std::string> fields;
  for (std::size_t n = 1; n + 1 < words.size(); n += 2) fields[words[n]] = words[n + 1];
  for (const char* key : {"fn", "approach", "ncontact", "iterations", "solve_s"}) {
    if (!fields.count(key)) lines.fail(std::string("'result' line lacks field '") + key + "'");
  }
  CaseResult<Scalar> stored;
  stored.normal_force = detail::parse_number<Scalar>(lines, fields["fn"], "fn");
  stored.approach = detail::parse_number<Scalar>(lines, fields["approach"], "approach");
  stored.contact_count = detail::parse_integer(lines, fields["ncontact"], "ncontact");
  stored.iterations = static_cast<int>(detail::parse_integer(lines, fields["iterations"], "iterations"));
  stored.solve_seconds = detail::parse_number<Scalar>(lines, fields["solve_s"], "solve_s");
  expect("p");
  stored.pressure = read_block("p", grid.size(), more);
  if (more) lines.fail("unexpected '" + words[0] + "' after the 'p' block");
  result_case.result = std::move(stored);
  return result_case;
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

/// Writes a case (and its result, if any) in the `.case` format, full precision.
template <typename Scalar>
void write_case(std::ostream& out, const Case<Scalar>& problem) {
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

}  // namespace fastnorm
