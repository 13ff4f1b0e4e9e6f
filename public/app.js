// Entry of the page. The viewer's modules live in web/, outside the served root; an import
// (unlike a <script src>) reaches them by file path, in the dev server and in the build.
import '../web/app/main.js';
