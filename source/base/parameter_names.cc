#include <rbc_ifem/base/input_error.h>
#include <rbc_ifem/base/parameter_names.h>
#include <rbc_ifem/base/parameter_text.h>

#include <algorithm>
#include <cctype>
#include <set>

namespace rbc_ifem
{
  namespace
  {
    /// The Levenshtein distance of @p a and @p b, letters without case.
    std::size_t
    edit_distance(const std::string &a, const std::string &b)
    {
      std::vector<std::size_t> row(b.size() + 1);
      for (std::size_t j = 0; j <= b.size(); ++j)
        row[j] = j;
      for (std::size_t i = 1; i <= a.size(); ++i)
        {
          std::size_t diagonal = row[0];
          row[0]               = i;
          for (std::size_t j = 1; j <= b.size(); ++j)
            {
              const bool same =
                std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                std::tolower(static_cast<unsigned char>(b[j - 1]));
              const std::size_t next =
                std::min({row[j] + 1, row[j - 1] + 1, diagonal + !same});
              diagonal = row[j];
              row[j]   = next;
            }
        }
      return row[b.size()];
    }

    /// What @p patterns declares below the subsection @p prefix ("" for
    /// the top level, else "A/B/"): its entries and its subsections.
    struct Declared
    {
      std::vector<std::string> entries, subsections;
    };

    Declared
    declared_in(const std::string                        &prefix,
                const std::map<std::string, std::string> &patterns)
    {
      Declared              declared;
      std::set<std::string> subsections;
      for (const auto &entry : patterns)
        {
          const std::string &path = entry.first;
          if (path.compare(0, prefix.size(), prefix) != 0)
            continue;
          const std::string rest  = path.substr(prefix.size());
          const std::size_t slash = rest.find('/');
          if (slash == std::string::npos)
            declared.entries.push_back(rest);
          else
            subsections.insert(rest.substr(0, slash));
        }
      declared.subsections.assign(subsections.begin(), subsections.end());
      return declared;
    }

    /// " Did you mean 'X'?" or "".
    std::string
    did_you_mean(const std::string              &name,
                 const std::vector<std::string> &candidates)
    {
      const std::string nearest = nearest_name(name, candidates);
      return nearest.empty() ? "" : " Did you mean '" + nearest + "'?";
    }

    /// " It is declared in subsection 'A/B'." for an entry @p name declared
    /// elsewhere, or "".
    std::string
    declared_elsewhere(const std::string                        &name,
                       const std::map<std::string, std::string> &patterns)
    {
      for (const auto &entry : patterns)
        {
          const std::size_t slash = entry.first.rfind('/');
          if (slash != std::string::npos &&
              entry.first.substr(slash + 1) == name)
            return " An entry '" + name + "' is in subsection '" +
                   entry.first.substr(0, slash) + "'.";
        }
      return "";
    }

    /// "the top level" or "subsection 'A/B'" for the prefix "A/B/".
    std::string
    place(const std::string &prefix)
    {
      return prefix.empty() ?
               "the top level" :
               "subsection '" + prefix.substr(0, prefix.size() - 1) + "'";
    }
  } // namespace

  std::string
  nearest_name(const std::string              &name,
               const std::vector<std::string> &candidates)
  {
    std::string nearest;
    std::size_t best = std::string::npos;
    for (const std::string &candidate : candidates)
      {
        const std::size_t distance = edit_distance(name, candidate);
        const std::size_t allowed =
          std::max<std::size_t>(2, std::max(name.size(), candidate.size()) / 3);
        if (distance <= allowed && distance < best)
          {
            best    = distance;
            nearest = candidate;
          }
      }
    return nearest;
  }

  void
  check_parameter_names(const std::string                        &text,
                        const std::string                        &filename,
                        const std::map<std::string, std::string> &patterns)
  {
    const std::string listing =
      "\nRun 'rbc-ifem --print-parameters' for every parameter, its "
      "allowed values and its default.";
    for (const ParameterLine &line : parameter_lines(text))
      {
        const std::string where = "in parameter file '" + filename +
                                  "', line " + std::to_string(line.number) +
                                  ": ";
        const Declared declared = declared_in(line.prefix, patterns);
        if (line.kind == ParameterLine::Kind::subsection &&
            std::find(declared.subsections.begin(),
                      declared.subsections.end(),
                      line.name) == declared.subsections.end())
          throw InputError(where + "there is no subsection '" + line.name +
                           "' in " + place(line.prefix) + "." +
                           did_you_mean(line.name, declared.subsections) +
                           listing);
        if (line.kind == ParameterLine::Kind::set &&
            patterns.count(line.prefix + line.name) == 0)
          throw InputError(where + "there is no parameter '" + line.name +
                           "' in " + place(line.prefix) + "." +
                           did_you_mean(line.name, declared.entries) +
                           declared_elsewhere(line.name, patterns) + listing);
      }
  }

  std::string
  suggest_parameter(const std::string                        &path,
                    const std::map<std::string, std::string> &patterns)
  {
    std::vector<std::string> paths;
    for (const auto &entry : patterns)
      paths.push_back(entry.first);
    const std::string nearest = nearest_name(path, paths);
    if (!nearest.empty())
      return " Did you mean '" + nearest + "'?";
    const std::size_t slash = path.rfind('/');
    return declared_elsewhere(
      slash == std::string::npos ? path : path.substr(slash + 1), patterns);
  }
} // namespace rbc_ifem
