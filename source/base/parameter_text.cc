#include <rbc_ifem/base/parameter_text.h>
#include <rbc_ifem/base/version.h>

#include <boost/property_tree/ptree.hpp>
#include <boost/property_tree/xml_parser.hpp>

#include <cctype>
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

  std::map<std::string, std::string>
  parameter_values(const std::string &text)
  {
    // A value ends at a comment (deal.II adds "# default: ..." to a value
    // that is not the default).
    static const std::regex set_line(R"(\s*set (.*?)\s*=\s*([^#]*?)\s*(#.*)?)");
    static const std::regex subsection_line(R"(\s*subsection (.*?)\s*)");
    static const std::regex end_line(R"(\s*end\s*)");
    std::istringstream      lines(text);
    std::string             line, path;
    std::vector<std::string>           subsections;
    std::map<std::string, std::string> values;
    while (std::getline(lines, line))
      {
        std::smatch m;
        if (std::regex_match(line, m, set_line))
          {
            path.clear();
            for (const std::string &subsection : subsections)
              path += subsection + '/';
            values[path + m[1].str()] = m[2];
          }
        else if (std::regex_match(line, m, subsection_line))
          subsections.push_back(m[1]);
        else if (std::regex_match(line, end_line) && !subsections.empty())
          subsections.pop_back();
      }
    return values;
  }

  std::string
  parameter_text(const ParameterHandler &prm)
  {
    const std::map<std::string, std::string> patterns = parameter_patterns(prm);

    std::ostringstream listing;
    prm.print_parameters(listing, ParameterHandler::PRM);
    std::istringstream lines(listing.str());

    // deal.II's listing, its title line replaced, an "Allowed" line put
    // before every set line: the subsections entered so far give its path.
    static const std::regex  set_line(R"((\s*)set (.*?)\s*=.*)");
    static const std::regex  subsection_line(R"(\s*subsection (.*))");
    static const std::regex  end_line(R"(\s*end\s*)");
    std::vector<std::string> subsections;
    std::string              line, text;
    // deal.II's title and its underline.
    std::getline(lines, line);
    std::getline(lines, line);
    text = "# Listing of Parameters of " + version_line() + '\n';
    while (std::getline(lines, line))
      {
        std::smatch m;
        if (std::regex_match(line, m, set_line))
          {
            std::string path;
            for (const std::string &subsection : subsections)
              path += subsection + '/';
            const auto pattern = patterns.find(path + m[2].str());
            if (pattern != patterns.end())
              text += comment_lines(allowed_values(pattern->second),
                                    m[1],
                                    "Allowed: ");
          }
        else if (std::regex_match(line, m, subsection_line))
          subsections.push_back(m[1]);
        else if (std::regex_match(line, end_line))
          subsections.pop_back();
        text += line + '\n';
      }
    return text;
  }
} // namespace rbc_ifem
