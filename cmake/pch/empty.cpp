// Empty: the translation unit that builds a precompiled header (cmake/PkmPch.cmake).
