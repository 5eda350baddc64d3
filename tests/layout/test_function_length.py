"""The function-length check of tools/lint (tracer_tools.lint.function_length) on files made here:
it names a function over the limit, in .cpp and .inl alike, and passes one at the limit."""

from tracer_tools.lint import function_length


def function_of(name: str, lines: int) -> str:
    """A C++ function `name` of exactly `lines` lines, signature to closing brace."""
    body = "".join(f"    x += {i};\n" for i in range(lines - 3))
    return f"int {name}(int x) {{\n{body}    return x;\n}}\n"


def test_a_long_function_is_named_with_its_place(tmp_path):
    (tmp_path / "a.cpp").write_text(function_of("short_enough", 80) + function_of("too_long", 81))
    (tmp_path / "b.inl").write_text("\n" + function_of("inline_too_long", 90))
    found = function_length.long_functions([tmp_path], 80)
    assert found == [
        f"{tmp_path / 'a.cpp'}:81: too_long is 81 lines",
        f"{tmp_path / 'b.inl'}:2: inline_too_long is 90 lines",
    ]
    assert function_length.main(["--limit", "80", str(tmp_path)]) == 1


def test_functions_at_the_limit_pass(tmp_path):
    (tmp_path / "a.h").write_text(function_of("at_the_limit", 80))
    assert function_length.long_functions([tmp_path], 80) == []
    assert function_length.main([str(tmp_path)]) == 0
