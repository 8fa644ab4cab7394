#pragma once
// USD's text format (.usda) as this exporter writes it: prims as nested blocks, attributes one
// a line, arrays on one line. Floats are written in their shortest form that reads back to the
// same float, so a stage holds exactly the values it was given.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <span>
#include <string>
#include <string_view>

namespace subdfit::exporter::usda {

std::string number(float value);
std::string number(double value);
std::string tuple(glm::vec2 value);
std::string tuple(glm::vec3 value);
std::string tuple(glm::vec4 value);
std::string quoted(std::string_view text);  // "text" with " and \ escaped

std::string array(std::span<const int> values);
std::string array(std::span<const float> values);
std::string array(std::span<const glm::vec2> values);
std::string array(std::span<const glm::vec3> values);

// Builds the layer's text: block() opens "header { ... }" around what follows until end().
class Layer {
public:
    void line(std::string_view text);
    void block(std::string_view header);
    void end();
    void blank() { text_ += '\n'; }
    // The text; every block ended.
    const std::string& text() const;

private:
    std::string text_;
    int depth_ = 0;
};

}  // namespace subdfit::exporter::usda
