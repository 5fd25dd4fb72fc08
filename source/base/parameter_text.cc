#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/base/parameter_text.h>
#include <rbc_ifem/base/version.h>

#include <boost/property_tree/ptree.hpp>
#include <boost/property_tree/xml_parser.hpp>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

namespace rbc_ifem
{
  namespace
  {
    /// A name of deal.II's XML output (every character but letters and
    /// digits written as _XX, XX its hex code) as the .prm file spells it.
    std::string
    demangle(const std::string &name)
    {
      std::string text;
      for (std::size_t i = 0; i < name.size(); ++i)
        if (name[i] == '_' && i + 2 < name.size() &&
            std::isxdigit(name[i + 1]) && std::isxdigit(name[i + 2]))
          {
            text += static_cast<char>(std::stoi(name.substr(i + 1, 2), 0, 16));
            i += 2;
          }
        else
          text += name[i];
      return text;
    }

    /// "Subsection/.../Entry" -> the entry's pattern description, for every
    /// entry below @p node of deal.II's XML listing.
    void
    collect_patterns(const boost::property_tree::ptree  &node,
                     const std::string                  &path,
                     std::map<std::string, std::string> &patterns)
    {
      for (const auto &[name, child] : node)
        {
          const std::string full = path + demangle(name);
          if (child.count("value") > 0)
            patterns[full] = child.get<std::string>("pattern_description");
          else
            collect_patterns(child, full + "/", patterns);
        }
    }

    /// How many items a list of @p low to @p high items has, in words.
    std::string
    list_length(const std::string &low, const std::string &high)
    {
      const bool unbounded = high == "4294967295" || high == "2147483647";
      if (low == high)
        return "exactly " + low;
      if (unbounded)
        return low == "0" ? "any number of" :
               low == "1" ? "one or more" :
                            "at least " + low;
      return low + " to " + high;
    }

    /// @p text broken into lines of at most @p width characters, each
    /// starting with @p indent and then "# " (the first with @p first).
    std::string
    comment_lines(const std::string &text,
                  const std::string &indent,
                  const std::string &first,
                  const std::size_t  width = 78)
    {
      std::istringstream words(text);
      std::string        word, line = indent + "# " + first, lines;
      const std::string  continuation =
        indent + "# " + std::string(first.size(), ' ');
      bool empty = true;
      while (words >> word)
        {
          if (!empty && line.size() + 1 + word.size() > width)
            {
              lines += line + '\n';
              line  = continuation;
              empty = true;
            }
          line += (empty ? "" : " ") + word;
          empty = false;
        }
      return lines + line + '\n';
    }
  } // namespace

  std::string
  allowed_values(const std::string &d)
  {
    std::smatch             m;
    static const std::regex real(
      R"(\[Double (\S+)\.\.\.(\S+) \(inclusive\)\])");
    static const std::regex integer(
      R"(\[Integer range (\S+)\.\.\.(\S+) \(inclusive\)\])");
    static const std::regex selection(R"(\[Selection (.*) \])");
    static const std::regex multiple(R"(\[MultipleSelection (.*) \])");
    static const std::regex list(
      R"(\[List of <(.*)> of length (\d+)\.\.\.(\d+) \(inclusive\)(?: separated by <(.*)>)?\])");
    const auto bounds = [](const std::string &kind,
                           const std::string &low,
                           const std::string &high,
                           const std::string &lowest,
                           const std::string &highest) {
      if (low == lowest && high == highest)
        return "any " + kind;
      if (high == highest)
        return "a " + kind + " ≥ " + low;
      if (low == lowest)
        return "a " + kind + " ≤ " + high;
      return "a " + kind + " from " + low + " to " + high;
    };
    const auto with_bars = [](std::string names) {
      return std::regex_replace(names, std::regex(R"(\|)"), " | ");
    };

    if (std::regex_match(d, m, real))
      return bounds("number", m[1], m[2], "-MAX_DOUBLE", "MAX_DOUBLE");
    if (std::regex_match(d, m, integer))
      return bounds("whole number", m[1], m[2], "-2147483648", "2147483647");
    if (d == "[Bool]")
      return "true | false";
    if (std::regex_match(d, m, selection))
      return "one of " + with_bars(m[1]);
    if (std::regex_match(d, m, multiple))
      return "a comma-separated list of any of " + with_bars(m[1]);
    if (d == "[Anything]")
      return "any text";
    if (d.rfind("[FileName", 0) == 0)
      return "a file name";
    if (d == "[DirectoryName]")
      return "a directory name";
    if (std::regex_match(d, m, list))
      {
        const std::string separator = m[4].matched ? m[4].str() : ",";
        return "a list of " + list_length(m[2], m[3]) +
               " items separated by '" + separator + "', each " +
               allowed_values(m[1]);
      }
    // Our own patterns describe themselves in words, within brackets.
    if (d.size() > 2 && d.front() == '[' && d.back() == ']')
      return d.substr(1, d.size() - 2);
    return d;
  }

  std::map<std::string, std::string>
  parameter_patterns(const ParameterHandler &prm)
  {
    std::stringstream xml;
    prm.print_parameters(xml, ParameterHandler::XML);
    boost::property_tree::ptree tree;
    boost::property_tree::read_xml(xml, tree);
    std::map<std::string, std::string> patterns;
    collect_patterns(tree.get_child("ParameterHandler"), "", patterns);
    return patterns;
  }

  std::vector<ParameterLine>
  parameter_lines(const std::string &text)
  {
    // A value ends at a comment (deal.II adds "# default: ..." to a value
    // that is not the default).
    static const std::regex set_line(
      R"(\s*set\s+(.*?)\s*=\s*([^#]*?)\s*(#.*)?)");
    static const std::regex subsection_line(
      R"(\s*subsection\s+(.*?)\s*(#.*)?)");
    static const std::regex    end_line(R"(\s*end\s*(#.*)?)");
    std::istringstream         lines(text);
    std::string                line, prefix;
    std::vector<std::size_t>   opened;
    std::vector<ParameterLine> result;
    for (unsigned int number = 1; std::getline(lines, line); ++number)
      {
        std::smatch   m;
        ParameterLine parsed{
          ParameterLine::Kind::other, "", "", prefix, number, line};
        if (std::regex_match(line, m, set_line))
          {
            parsed.kind  = ParameterLine::Kind::set;
            parsed.name  = m[1];
            parsed.value = m[2];
          }
        else if (std::regex_match(line, m, subsection_line))
          {
            parsed.kind = ParameterLine::Kind::subsection;
            parsed.name = m[1];
            opened.push_back(prefix.size());
            prefix += parsed.name + '/';
          }
        else if (std::regex_match(line, end_line) && !opened.empty())
          {
            parsed.kind = ParameterLine::Kind::end;
            prefix.resize(opened.back());
            opened.pop_back();
          }
        result.push_back(parsed);
      }
    return result;
  }

  void
  set_entry(ParameterHandler  &prm,
            const std::string &path,
            const std::string &value)
  {
    std::vector<std::string> names = Utilities::split_string_list(path, '/');
    const std::string        entry = names.back();
    names.pop_back();
    for (const std::string &subsection : names)
      prm.enter_subsection(subsection);
    try
      {
        prm.set(entry, value);
      }
    catch (...)
      {
        for (std::size_t i = 0; i < names.size(); ++i)
          prm.leave_subsection();
        throw;
      }
    for (std::size_t i = 0; i < names.size(); ++i)
      prm.leave_subsection();
  }

  std::vector<ParameterEntry>
  parameter_entries(const std::string &text)
  {
    std::vector<ParameterEntry> entries;
    for (const ParameterLine &line : parameter_lines(text))
      if (line.kind == ParameterLine::Kind::set)
        entries.push_back({line.prefix + line.name, line.value, line.number});
    return entries;
  }

  std::map<std::string, std::string>
  parameter_values(const std::string &text)
  {
    std::map<std::string, std::string> values;
    for (const ParameterEntry &entry : parameter_entries(text))
      values[entry.path] = entry.value;
    return values;
  }

  std::string
  read_parameter_file(const std::string        &filename,
                      std::vector<std::string> &warnings)
  {
    std::ifstream      in(filename, std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    std::string text = bytes.str();
    // Editors on some systems start a UTF-8 file with a byte-order mark,
    // which deal.II would read as part of the first line.
    const std::string byte_order_mark = "\xEF\xBB\xBF";
    if (text.compare(0, byte_order_mark.size(), byte_order_mark) == 0)
      text.erase(0, byte_order_mark.size());

    const std::vector<ParameterEntry>   entries = parameter_entries(text);
    std::map<std::string, unsigned int> first;
    for (const ParameterEntry &entry : entries)
      if (!first.emplace(entry.path, entry.line).second)
        warnings.push_back(filename + ", line " + std::to_string(entry.line) +
                           ": " + entry.path + " is set again (first on line " +
                           std::to_string(first[entry.path]) +
                           "); this later value, " + entry.value +
                           ", is the one used.");
    if (entries.empty())
      warnings.push_back(filename +
                         " sets no parameter: every one keeps its default "
                         "(rbc-ifem --print-parameters lists them).");
    return text;
  }

  void
  check_magnitudes(const ParameterHandler &prm)
  {
    const auto patterns = parameter_patterns(prm);
    for (const auto &[path, value] : parameter_values(parameter_text(prm)))
      {
        // Names, switches and whole numbers (counts, seeds) are not
        // physical values; every other number is, "auto" aside.
        const auto pattern = patterns.find(path);
        if (pattern == patterns.end() ||
            std::regex_search(pattern->second,
                              std::regex("Integer|Bool|Selection|FileName|"
                                         "DirectoryName")))
          continue;
        // Lists separate their numbers by ',' and their items by ';'.
        std::string numbers = value;
        std::replace(numbers.begin(), numbers.end(), ';', ',');
        for (const std::string &word : Utilities::split_string_list(numbers))
          {
            char        *end    = nullptr;
            const double number = std::strtod(word.c_str(), &end);
            if (end == word.c_str() || number == 0.)
              continue;
            if (!std::isfinite(number) || std::abs(number) < 1e-15 ||
                std::abs(number) > 1e15)
              throw InputError(path,
                               value,
                               "a number of magnitude between 1e-15 and 1e15, "
                               "or 0: in the units of its documentation "
                               "(µm, s, pN) no physical value lies outside, "
                               "and " +
                                 word +
                                 " would overflow or vanish in the "
                                 "solvers.");
          }
      }
  }

  std::string
  parameter_text(const ParameterHandler &prm)
  {
    const std::map<std::string, std::string> patterns = parameter_patterns(prm);

    std::ostringstream listing;
    prm.print_parameters(listing, ParameterHandler::PRM);

    // deal.II's listing, its title line replaced (the title and its
    // underline, lines 1 and 2), an "Allowed" line put before every set line.
    std::string text = "# Listing of Parameters of " + version_line() + '\n';
    for (const ParameterLine &line : parameter_lines(listing.str()))
      {
        if (line.number <= 2)
          continue;
        const auto pattern = patterns.find(line.prefix + line.name);
        if (line.kind == ParameterLine::Kind::set && pattern != patterns.end())
          text += comment_lines(allowed_values(pattern->second),
                                line.text.substr(0, line.text.find("set")),
                                "Allowed: ");
        text += line.text + '\n';
      }
    return text;
  }
} // namespace rbc_ifem
