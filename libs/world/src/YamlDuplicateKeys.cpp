#include "YamlDuplicateKeys.h"

#include <map>
#include <sstream>
#include <vector>

namespace daep::world {
namespace {

/** The keys seen so far in one open mapping, with the line of each. */
using KeySet = std::map<std::string, int>;

/** A block mapping whose keys start at column `indent`. */
struct BlockLevel {
    std::size_t indent;
    KeySet keys;
};

/** Flow collections ({...} and [...]) read character by character, across lines. */
class FlowScanner {
public:
    bool open() const { return !frames_.empty(); }

    /** Scans line text from column `from`; returns a duplicate if one closes the scan. */
    std::optional<DuplicateKey> scan(const std::string& s, std::size_t from, int line) {
        for (std::size_t i = from; i < s.size(); ++i) {
            const char c = s[i];
            if (c == '#' && (i == 0 || s[i - 1] == ' ' || s[i - 1] == '\t'))
                break;
            if (c == '"' || c == '\'') {
                i = skipQuoted(s, i);
                continue;
            }
            if (c == '{' || c == '[') {
                frames_.push_back({c == '{', {}, "", false});
                continue;
            }
            if (frames_.empty())
                continue;
            Frame& f = frames_.back();
            if (c == '}' || c == ']') {
                frames_.pop_back();
                if (!frames_.empty())
                    frames_.back().afterValue = true;
                continue;
            }
            if (!f.mapping)
                continue;
            if (c == ',') {
                f.pending.clear();
                f.afterValue = false;
                continue;
            }
            if (c == ':' && !f.afterValue && isColonEnd(s, i)) {
                if (auto dup = addKey(f, trim(f.pending), line))
                    return dup;
                f.pending.clear();
                f.afterValue = true;
                continue;
            }
            if (!f.afterValue)
                f.pending += c;
        }
        return std::nullopt;
    }

    static bool isColonEnd(const std::string& s, std::size_t i) {
        return i + 1 >= s.size() || s[i + 1] == ' ' || s[i + 1] == ',' || s[i + 1] == '}' ||
               s[i + 1] == ']' || s[i + 1] == '\t';
    }

    static std::size_t skipQuoted(const std::string& s, std::size_t i) {
        const char q = s[i];
        for (std::size_t j = i + 1; j < s.size(); ++j) {
            if (q == '"' && s[j] == '\\') {
                ++j;
                continue;
            }
            if (s[j] == q) {
                if (q == '\'' && j + 1 < s.size() && s[j + 1] == '\'') {
                    ++j;  // '' is an escaped quote
                    continue;
                }
                return j;
            }
        }
        return s.size();
    }

    static std::string trim(const std::string& s) {
        const auto b = s.find_first_not_of(" \t");
        if (b == std::string::npos)
            return "";
        const auto e = s.find_last_not_of(" \t");
        std::string k = s.substr(b, e - b + 1);
        if (k.size() >= 2 && (k.front() == '"' || k.front() == '\'') && k.back() == k.front())
            k = k.substr(1, k.size() - 2);
        return k;
    }

    static std::optional<DuplicateKey> addKey(KeySet& keys, const std::string& key, int line) {
        const auto [it, inserted] = keys.emplace(key, line);
        if (inserted)
            return std::nullopt;
        return DuplicateKey{key, line, it->second};
    }

private:
    struct Frame {
        bool mapping;
        KeySet keys;
        std::string pending;  ///< text of the entry's key so far
        bool afterValue;      ///< past this entry's ':'
    };

    static std::optional<DuplicateKey> addKey(Frame& f, const std::string& key, int line) {
        return addKey(f.keys, key, line);
    }

    std::vector<Frame> frames_;
};

/** Block structure, line by line; flow collections go to the FlowScanner. */
class BlockScanner {
public:
    std::optional<DuplicateKey> line(const std::string& raw, int number) {
        if (flow_.open())
            return flow_.scan(raw, 0, number);
        const std::size_t indent = raw.find_first_not_of(' ');
        if (indent == std::string::npos || raw[indent] == '#' || raw[indent] == '\r')
            return std::nullopt;
        if (blockScalarIndent_ && indent > *blockScalarIndent_)
            return std::nullopt;
        blockScalarIndent_.reset();
        if (raw.compare(indent, 3, "---") == 0 || raw.compare(indent, 3, "...") == 0) {
            levels_.clear();
            return std::nullopt;
        }
        std::size_t col = indent;
        while (col < raw.size() && raw[col] == '-' &&
               (col + 1 == raw.size() || raw[col + 1] == ' ')) {
            popDeeperThan(col);  // a new list item starts a new mapping
            col = raw.find_first_not_of(' ', col + 1);
            if (col == std::string::npos)
                return std::nullopt;
        }
        return content(raw, col, number);
    }

private:
    std::optional<DuplicateKey> content(const std::string& raw, std::size_t col, int number) {
        if (raw[col] == '{' || raw[col] == '[')
            return flow_.scan(raw, col, number);
        const std::size_t colon = keyColon(raw, col);
        if (colon == std::string::npos)
            return std::nullopt;  // a plain scalar or a continuation line
        popDeeperThan(col);
        if (levels_.empty() || levels_.back().indent < col)
            levels_.push_back({col, {}});
        const std::string key = FlowScanner::trim(raw.substr(col, colon - col));
        if (auto dup = FlowScanner::addKey(levels_.back().keys, key, number))
            return dup;
        const std::size_t value = raw.find_first_not_of(" \t", colon + 1);
        if (value == std::string::npos)
            return std::nullopt;
        if (raw[value] == '|' || raw[value] == '>')
            blockScalarIndent_ = col;
        else if (raw[value] == '{' || raw[value] == '[')
            return flow_.scan(raw, value, number);
        return std::nullopt;
    }

    /** Column of the ':' that ends a block key starting at col, or npos. */
    static std::size_t keyColon(const std::string& s, std::size_t col) {
        std::size_t i = col;
        if (s[i] == '"' || s[i] == '\'')
            i = FlowScanner::skipQuoted(s, i) + 1;
        for (; i < s.size(); ++i) {
            if (s[i] == '#' && (s[i - 1] == ' ' || s[i - 1] == '\t'))
                return std::string::npos;
            if (s[i] == ':' &&
                (i + 1 >= s.size() || s[i + 1] == ' ' || s[i + 1] == '\t' || s[i + 1] == '\r'))
                return i;
        }
        return std::string::npos;
    }

    void popDeeperThan(std::size_t col) {
        while (!levels_.empty() && levels_.back().indent > col)
            levels_.pop_back();
    }

    std::vector<BlockLevel> levels_;
    FlowScanner flow_;
    std::optional<std::size_t> blockScalarIndent_;
};

}  // namespace

std::optional<DuplicateKey> findDuplicateKey(const std::string& text) {
    BlockScanner scanner;
    std::istringstream in(text);
    int number = 0;
    for (std::string l; std::getline(in, l);) {
        if (auto dup = scanner.line(l, ++number))
            return dup;
    }
    return std::nullopt;
}

}  // namespace daep::world
