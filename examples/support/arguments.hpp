// The command-line parser of fastnorm's tools (fastnorm-solve, fastnorm-wheelrail,
// fastnorm-bench, wheelrail_study): typed options with units and ranges, `--help` with
// every default, and one way of failing — a message that names the option and repeats
// what the user typed, in the user's units, and exit status 2.
//
//   fastnorm_example::CommandLine line("fastnorm-tool", "what it does");
//   line.option("--y", y_mm, "MM", "lateral shift of the wheelset", fastnorm_example::within(-30, 30));
//   line.flag("--compare", compare, "also solve with full NORM");
//   return fastnorm_example::run_tool(line, argc, argv, [&] { ...; return 0; });
//
// Numbers must be read whole and finite ("3mm", "nan" and "1e999" are refused); whole
// numbers must be whole; a list option takes comma-separated items. A dependency-free
// header rather than CLI11: the tools need a few dozen lines of it, and CLI11 accepts NaN
// for a ranged number and adds seconds of compile time to every tool.
#pragma once

#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <limits>
#include <new>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace fastnorm_example {

/// A mistake on the command line; run_tool prints it with the usage line, exit status 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The values a number option accepts: from min to max, each end included or not.
struct Range {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_excluded = false, max_excluded = false;
};
inline Range within(double min, double max) { return {min, max, false, false}; }
inline Range strictly_within(double min, double max) { return {min, max, true, true}; }
inline Range at_least(double min) { return {min, std::numeric_limits<double>::infinity(), false, false}; }
inline Range positive() { return {0, std::numeric_limits<double>::infinity(), true, false}; }

namespace detail {

inline std::string shown(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

inline std::string describe(const Range& range) {
  const bool below = std::isfinite(range.min), above = std::isfinite(range.max);
  if (below && above) {
    return (range.min_excluded ? "in (" : "in [") + shown(range.min) + ", " + shown(range.max) +
           (range.max_excluded ? ")" : "]");
  }
  if (below) return (range.min_excluded ? "> " : ">= ") + shown(range.min);
  if (above) return (range.max_excluded ? "< " : "<= ") + shown(range.max);
  return "";
}

inline bool contains(const Range& range, double value) {
  return (range.min_excluded ? value > range.min : value >= range.min) &&
         (range.max_excluded ? value < range.max : value <= range.max);
}

// A finite number read from the whole of `text`.
inline double read_number(const std::string& option, const std::string& text) {
  char* end = nullptr;
  const double value = text.empty() ? 0.0 : std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(value)) {
    throw UsageError(option + " needs a number, not '" + text + "'");
  }
  return value;
}

// The limits are in the option's own units, the ones the user typed.
inline void check_range(const std::string& option, const std::string& text, double value, const Range& range) {
  if (!contains(range, value)) throw UsageError(option + " must be " + describe(range) + ", not " + text);
}

// One item (an option's value or an item of its list) read as T and checked.
template <typename T>
T read_item(const std::string& option, const std::string& text, const Range& range) {
  if constexpr (std::is_same_v<T, std::string>) {
    return text;
  } else {
    static_assert(std::is_arithmetic_v<T>, "an option holds a number, a string or a list of them");
    const double value = read_number(option, text);
    if (std::is_integral_v<T> && value != std::floor(value)) {
      throw UsageError(option + " needs a whole number, not '" + text + "'");
    }
    check_range(option, text, value, range);
    return static_cast<T>(value);
  }
}

template <typename T>
struct is_list : std::false_type {};
template <typename T>
struct is_list<std::vector<T>> : std::true_type {};

template <typename T>
std::string default_text(const T& value) {
  if constexpr (is_list<T>::value) {
    std::string text;
    for (const auto& item : value) text += (text.empty() ? "" : ",") + default_text(item);
    return text;
  } else if constexpr (std::is_same_v<T, std::string>) {
    return value;
  } else {
    return shown(static_cast<double>(value));
  }
}

}  // namespace detail

/// A tool's options, positional arguments and help text.
class CommandLine {
 public:
  CommandLine(std::string program, std::string summary) : program_(std::move(program)), summary_(std::move(summary)) {}

  const std::string& program() const { return program_; }

  /// `name VALUE`: a number (range checked), a string, or a comma-separated list of either.
  /// `value` holds the default until parse() and is shown by --help; `unit` names the
  /// value in the help line (MM, N, DEG, FILE, …).
  template <typename T>
  CommandLine& option(const std::string& name, T& value, const std::string& unit, const std::string& help,
                    Range range = {}) {
    auto read = [name, range, &value](const std::string& text) {
      if constexpr (detail::is_list<T>::value) {
        value.clear();
        std::istringstream items(text);
        for (std::string item; std::getline(items, item, ',');) {
          value.push_back(detail::read_item<typename T::value_type>(name, item, range));
        }
        if (value.empty()) throw UsageError(name + " needs at least one item");
      } else {
        value = detail::read_item<T>(name, text, range);
      }
    };
    std::string described = help;
    const std::string limits = detail::describe(range);
    if (!limits.empty()) described += "; " + limits;
    const std::string shown_default = detail::default_text(value);
    if (!shown_default.empty()) described += " (default " + shown_default + ")";
    options_.push_back({name, unit, described, read, false});
    return *this;
  }

  /// `name WORD`, one of `allowed`.
  CommandLine& choice(const std::string& name, std::string& value, const std::vector<std::string>& allowed,
                    const std::string& help) {
    std::string listed;
    for (const auto& word : allowed) listed += (listed.empty() ? "" : "|") + word;
    auto read = [name, allowed, listed, &value](const std::string& text) {
      for (const auto& word : allowed) {
        if (word == text) {
          value = text;
          return;
        }
      }
      throw UsageError(name + " must be " + listed + ", not '" + text + "'");
    };
    options_.push_back({name, listed, help + (value.empty() ? "" : " (default " + value + ")"), read, false});
    return *this;
  }

  /// `name` alone: sets `value` to true.
  CommandLine& flag(const std::string& name, bool& value, const std::string& help) {
    options_.push_back({name, "", help, [&value](const std::string&) { value = true; }, true});
    return *this;
  }

  /// The words that are not options: exactly one, or any number (none too) when `many`.
  CommandLine& positional(const std::string& name, std::vector<std::string>& values, const std::string& help,
                        bool many = false) {
    positional_ = {name, help, &values, many};
    return *this;
  }

  /// Whether the user gave `name` (after parse()).
  bool given(const std::string& name) const {
    for (const auto& word : given_) {
      if (word == name) return true;
    }
    return false;
  }

  std::string usage() const {
    std::string line = "usage: " + program_ + " [options]";
    if (positional_.values) line += " " + positional_.name + (positional_.many ? "..." : "");
    return line + "\n";
  }

  std::string help() const {
    std::string text = usage() + "\n" + summary_ + "\n\n";
    if (positional_.values) text += "  " + positional_.name + "\n      " + positional_.help + "\n";
    for (const auto& option : options_) {
      text += "  " + option.name + (option.is_flag ? "" : " " + option.unit) + "\n      " + option.help + "\n";
    }
    return text + "  --help\n      this text\n";
  }

  /// Reads argv; returns false after printing the help for --help or -h. Throws UsageError.
  bool parse(int argc, char** argv) {
    std::vector<std::string> words;
    for (int n = 1; n < argc; ++n) {
      const std::string word = argv[n];
      if (word == "--help" || word == "-h") {
        std::cout << help();
        return false;
      }
      if (word.size() > 1 && word[0] == '-' && !is_number(word)) {
        const Option& option = find(word);
        if (!option.is_flag && n + 1 >= argc) throw UsageError("option " + word + " needs a value");
        option.read(option.is_flag ? std::string() : std::string(argv[++n]));
        given_.push_back(word);
      } else {
        words.push_back(word);
      }
    }
    if (!positional_.values) {
      if (!words.empty()) throw UsageError("unexpected argument '" + words.front() + "'");
      return true;
    }
    if (!positional_.many && words.empty()) throw UsageError("no " + positional_.name + " given");
    if (!positional_.many && words.size() > 1) {
      throw UsageError("more than one " + positional_.name + " given ('" + words[1] + "')");
    }
    *positional_.values = words;
    return true;
  }

 private:
  struct Option {
    std::string name, unit, help;
    std::function<void(const std::string&)> read;
    bool is_flag;
  };
  struct Positional {
    std::string name, help;
    std::vector<std::string>* values = nullptr;
    bool many = false;
  };

  static bool is_number(const std::string& word) {
    char* end = nullptr;
    std::strtod(word.c_str(), &end);
    return end == word.c_str() + word.size();
  }

  const Option& find(const std::string& word) const {
    for (const auto& option : options_) {
      if (option.name == word) return option;
    }
    throw UsageError("unknown option '" + word + "'");
  }

  std::string program_, summary_;
  std::vector<Option> options_;
  Positional positional_;
  std::vector<std::string> given_;
};

/// Parses, then runs `body` (returning the exit status). A bad command line, and any error
/// `body` throws (the library's invalid_argument for a bad file, solver name or value; a
/// file that cannot be written), print one message naming the culprit and give status 2;
/// running out of memory says so; --help gives 0.
template <typename Body>
int run_tool(CommandLine& line, int argc, char** argv, Body&& body) {
  try {
    if (!line.parse(argc, argv)) return 0;
    return body();
  } catch (const UsageError& error) {
    std::cerr << line.program() << ": " << error.what() << '\n'
              << line.usage() << "(" << line.program() << " --help lists the options)\n";
  } catch (const std::bad_alloc&) {
    std::cerr << line.program() << ": out of memory: the problem is too large for this machine\n";
  } catch (const std::exception& error) {
    std::cerr << line.program() << ": " << error.what() << '\n';
  }
  return 2;
}

}  // namespace fastnorm_example
